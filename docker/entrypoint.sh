#!/bin/sh
# The image's one entry point: `netmc ARGS`, `netmc-server ARGS` or `netmc-axis ARGS` (the first
# word picks the program; anything else is handed to netmc). Flags may also come from NETMC_*
# environment variables (docs/operations/lab-deployment.md). No argument: netmc's in-process study.
set -e
case "${1:-}" in
  netmc | netmc-server | netmc-axis) program=$1; shift; exec "/usr/bin/$program" "$@" ;;
  "") exec /usr/bin/netmc sim ;;
  *) exec /usr/bin/netmc "$@" ;;
esac
