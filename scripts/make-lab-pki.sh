#!/usr/bin/env bash
# A lab's DDS Security material for netmc: a certificate authority, one certificate per DDS
# participant and the signed governance and permissions that say who may write what.
#
#   scripts/make-lab-pki.sh DIR --server NAME [--server NAME ...] --node NAME:AXIS[,AXIS...] [...]
#                               [--reader NAME ...] [--management HOST ...] [--management-client NAME ...]
#
# Every participant gets DIR/NAME.pem (certificate) and DIR/NAME.key (its private key, 0600);
# all share DIR/ca.pem, DIR/governance.p7s and DIR/permissions.p7s. Start each process with
# `--security DIR` and its name (netmc-server --dds-name NAME, netmc-axis --node NAME).
# Permissions (everything else is denied):
#   server  writes job control, setpoints, clock probes and iteration logs; reads feedback,
#           axis events, node status and clock replies;
#   node    writes feedback and axis events only in the partitions of its own axes, its status
#           and clock replies; reads job control, setpoints, clock probes and node status;
#   reader  reads iteration logs and node status (a monitor), writes nothing.
# Governance: no unauthenticated participant joins; discovery, liveliness and every topic's
# data are encrypted (AES-GCM) and access-controlled. Topics are named one by one (a * in a
# topic name does not cross a /).
# --management HOST (repeatable): DIR/management.pem and .key, a TLS server certificate for the
# management endpoint (netmc-server --tls-cert/--tls-key) naming each HOST (an IP address or a
# DNS name) as the clients dial it; clients trust DIR/ca.pem (NETMC_TLS_CA).
# --management-client NAME (repeatable): DIR/NAME.pem and .key, a TLS client certificate for a
# server started with --tls-client-ca DIR/ca.pem (clients: NETMC_TLS_CERT, NETMC_TLS_KEY); no
# DDS permission.
# Run again on a lab's DIR it adds what is missing (participants, their grants, the management
# certificate) signed by the lab's CA, and never replaces the CA, a key or a certificate: a name
# asked for with other permissions, a management certificate for other hosts or a CA certificate
# without its key is refused, nothing written.
# Needs openssl. Keys are ECDSA P-256; certificates and permissions hold for 10 years.
set -euo pipefail

usage() {
  echo "usage: $0 DIR --server NAME [...] --node NAME:AXIS[,AXIS...] [...] [--reader NAME ...] [--management HOST ...] [--management-client NAME ...]" >&2
  exit 2
}
[ $# -ge 1 ] || usage
dir=$1
shift
servers=()
nodes=()
readers=()
management=()
management_clients=()
while [ $# -gt 0 ]; do
  [ $# -ge 2 ] || usage
  case "$1" in
    --server) servers+=("$2") ;;
    --node) nodes+=("$2") ;;
    --reader) readers+=("$2") ;;
    --management) management+=("$2") ;;
    --management-client) management_clients+=("$2") ;;
    *) usage ;;
  esac
  shift 2
done
[ ${#servers[@]} -gt 0 ] || usage
name_ok() { [[ "$1" =~ ^[A-Za-z0-9_.-]{1,64}$ ]] || { echo "$0: bad name '$1' (1-64 of A-Z a-z 0-9 _ . -)" >&2; exit 2; }; }

# The hosts of the management certificate, checked before anything is written.
alt=""
for host in "${management[@]}"; do
  if [[ "$host" =~ ^[0-9]{1,3}(\.[0-9]{1,3}){3}$ || "$host" =~ ^[0-9A-Fa-f:]*:[0-9A-Fa-f:]*$ ]]; then
    alt+="${alt:+,}IP:$host"
  elif [[ "$host" =~ ^[A-Za-z0-9]([A-Za-z0-9.-]{0,252})$ ]]; then
    alt+="${alt:+,}DNS:$host"
  else
    echo "$0: --management: bad host '$host' (an IP address or a DNS name)" >&2
    exit 2
  fi
done
for client in "${management_clients[@]}"; do name_ok "$client"; done
for s in "${servers[@]}" "${readers[@]}"; do name_ok "$s"; done
for spec in "${nodes[@]}"; do
  node=${spec%%:*}
  axes=${spec#*:}
  [ "$node" != "$spec" ] && [ -n "$axes" ] || usage
  name_ok "$node"
  for axis in ${axes//,/ }; do name_ok "$axis"; done
done

mkdir -p "$dir"
umask 077
cd "$dir"

# A lab's directory is added to, never replaced: its CA, keys and certificates are what the
# running nodes hold (a new CA would make every one of them a stranger). Everything is checked
# before anything is written; a conflict is refused with what to do.
refuse() { echo "$0: $dir: $*; nothing written (a lab's CA, keys and certificates are never replaced)" >&2; exit 1; }
if [ -e ca.pem ] || [ -e ca.key ]; then
  [ -e ca.pem ] && [ -e ca.key ] || refuse "ca.pem and ca.key must both be here to sign with the lab's CA (restore the missing one, or use a new directory for a new lab)"
fi
[ ! -e permissions.p7s ] || [ -e permissions.xml ] ||
  refuse "permissions.p7s without permissions.xml: the grants it signs cannot be extended (restore permissions.xml)"
# An existing participant's certificate and key are kept, if they are the CA's and a pair.
reusable() {  # reusable NAME: 0 if NAME.pem and NAME.key are here (checked), 1 if neither
  [ -e "$1.pem" ] || [ -e "$1.key" ] || return 1
  [ -e "$1.pem" ] && [ -e "$1.key" ] || refuse "$1: one of $1.pem and $1.key is missing (restore it, or choose another name)"
  openssl verify -CAfile ca.pem "$1.pem" >/dev/null 2>&1 || refuse "$1.pem is not signed by this directory's ca.pem"
  [ "$(openssl x509 -in "$1.pem" -noout -pubkey)" == "$(openssl pkey -in "$1.key" -pubout)" ] ||
    refuse "$1.key is not the key of $1.pem"
  return 0
}
for name in "${servers[@]}" "${readers[@]}" "${nodes[@]%%:*}" "${management_clients[@]}"; do reusable "$name" || true; done
if reusable management && [ -n "$alt" ]; then
  have=$(openssl x509 -in management.pem -noout -ext subjectAltName | tail -n +2 | tr -d ' ' | sed 's/IPAddress:/IP:/g')
  [ "$have" == "$alt" ] ||
    refuse "management.pem names $have, not $alt (move management.pem and management.key away to issue one for these hosts)"
fi

ca_state="CA kept"
[ -e ca.pem ] || {
  ca_state="new CA"
  openssl ecparam -name prime256v1 -genkey -noout -out ca.key
  openssl req -x509 -new -key ca.key -sha256 -days 3650 -subj "/CN=netmc lab CA" -out ca.pem 2>/dev/null
}

issued=()
# issue NAME [SUBJECT [EXTENSIONS]]: NAME.key and NAME.pem signed by the CA, for SUBJECT (default
# /CN=NAME), with the X.509 extensions given (lines of an openssl extfile; default none); an
# existing pair (checked above) is kept.
issue() {
  [ ! -e "$1.pem" ] || return 0
  issued+=("$1")
  openssl ecparam -name prime256v1 -genkey -noout -out "$1.key"
  openssl req -new -key "$1.key" -sha256 -subj "${2:-/CN=$1}" -out "$1.csr" 2>/dev/null
  printf '%s' "${3:-}" >"$1.ext"
  openssl x509 -req -in "$1.csr" -CA ca.pem -CAkey ca.key -CAcreateserial -sha256 -days 3650 \
    ${3:+-extfile "$1.ext"} -out "$1.pem" 2>/dev/null
  rm -f "$1.csr" "$1.ext"
}

topics() {  # topics T...: <topic> elements
  for t in "$@"; do printf '            <topic>%s</topic>\n' "$t"; done
}

# rule PUBLISH_TOPICS SUBSCRIBE_TOPICS [PUBLISH_PARTITIONS [SUBSCRIBE_PARTITIONS]]: one
# <allow_rule> (lists space-separated). Without partitions a rule covers only the default
# (empty) partition; "*" covers every partition.
rule() {
  echo "      <allow_rule>"
  echo "        <domains><id_range><min>0</min><max>230</max></id_range></domains>"
  local kind list partitions
  for kind in publish subscribe; do
    if [ "$kind" = publish ]; then list=$1; partitions=${3:-}; else list=$2; partitions=${4:-}; fi
    [ -n "$list" ] || continue
    echo "        <$kind>"
    echo "          <topics>"
    # shellcheck disable=SC2086
    topics $list
    echo "          </topics>"
    if [ -n "$partitions" ]; then
      echo "          <partitions>"
      for p in $partitions; do printf '            <partition>%s</partition>\n' "$p"; done
      echo "          </partitions>"
    fi
    echo "        </$kind>"
  done
  echo "      </allow_rule>"
}

# grant NAME RULES: the <grant> of NAME's certificate, everything not allowed denied
grant() {
  cat <<XML
    <grant name="$1">
      <subject_name>CN=$1</subject_name>
      <validity><not_before>2020-01-01T00:00:00</not_before><not_after>2036-01-01T00:00:00</not_after></validity>
$2
      <default>DENY</default>
    </grant>
XML
}

# grant_of NAME: the <grant> NAME's role gives it (servers, nodes, readers as named).
declare -A grants=()
order=()
for s in "${servers[@]}"; do
  # The per-axis topics live in the axes' partitions, the others in the default one.
  grants[$s]=$(grant "$s" "$(rule "netmc/v4/lockstep/setpoint netmc/v4/realtime/setpoint" \
    "netmc/v4/lockstep/feedback netmc/v4/realtime/feedback netmc/v4/axis_event" "netmc.axis.*" "netmc.axis.*")
$(rule "netmc/v4/job_control netmc/v4/clock_probe netmc/v4/iteration_log" \
    "netmc/v4/node_status netmc/v4/clock_reply")")
  order+=("$s")
done
for spec in "${nodes[@]}"; do
  node=${spec%%:*}
  axes=${spec#*:}
  partitions=""
  for axis in ${axes//,/ }; do partitions+=" netmc.axis.$axis"; done
  # Feedback and events only in its axes' partitions, their setpoints; its status and clock
  # replies, job control and probes in the default partition.
  grants[$node]=$(grant "$node" "$(rule "netmc/v4/lockstep/feedback netmc/v4/realtime/feedback netmc/v4/axis_event" \
    "netmc/v4/lockstep/setpoint netmc/v4/realtime/setpoint" "$partitions" "$partitions")
$(rule "netmc/v4/node_status netmc/v4/clock_reply" "netmc/v4/job_control netmc/v4/clock_probe netmc/v4/node_status")")
  order+=("$node")
done
for r in "${readers[@]}"; do
  grants[$r]=$(grant "$r" "$(rule "" "netmc/v4/iteration_log netmc/v4/node_status")")
  order+=("$r")
done

# The lab's permissions keep every grant they hold: a name already granted must be asked for with
# the same permissions; new names are added.
added=()
for name in "${order[@]}"; do
  if [ -e permissions.xml ] && grep -q "<grant name=\"$name\">" permissions.xml; then
    held=$(awk -v open="<grant name=\"$name\">" 'index($0, open) {on = 1} on {print} on && /<\/grant>/ {exit}' permissions.xml)
    [ "$held" == "${grants[$name]}" ] ||
      refuse "$name: already in permissions.xml with other permissions than asked (choose another name, or a new directory for a new lab)"
  else
    added+=("$name")
  fi
done

for name in "${order[@]}"; do issue "$name"; done
# The management endpoint's TLS certificate (each host as the clients dial it), and its clients'.
[ -z "$alt" ] || issue management "/CN=netmc management" \
  "$(printf 'basicConstraints=critical,CA:FALSE\nsubjectAltName=%s\nextendedKeyUsage=serverAuth' "$alt")"
for client in "${management_clients[@]}"; do
  issue "$client" "" "$(printf 'basicConstraints=critical,CA:FALSE\nextendedKeyUsage=clientAuth')"
done

if [ ! -e permissions.xml ]; then
  {
    echo '<?xml version="1.0" encoding="UTF-8"?>'
    echo '<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="omg_shared_ca_permissions.xsd">'
    echo '  <permissions>'
    for name in "${added[@]}"; do echo "${grants[$name]}"; done
    echo '  </permissions>'
    echo '</dds>'
  } >permissions.xml
  sign=(permissions)
elif [ ${#added[@]} -gt 0 ]; then
  # The new grants go before the closing tag; the old ones stay as they were.
  {
    grep -v '^  </permissions>$' permissions.xml | grep -v '^</dds>$'
    for name in "${added[@]}"; do echo "${grants[$name]}"; done
    echo '  </permissions>'
    echo '</dds>'
  } >permissions.xml.new
  mv permissions.xml.new permissions.xml
  sign=(permissions)
else
  sign=()
fi
[ -e permissions.p7s ] || sign=(permissions)

[ -e governance.p7s ] || cat >governance.xml <<'XML'
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="omg_shared_ca_governance.xsd">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>230</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>false</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
XML

[ -e governance.p7s ] || sign+=(governance)
for doc in "${sign[@]}"; do
  openssl smime -sign -in "$doc.xml" -text -out "$doc.p7s" -signer ca.pem -inkey ca.key
done
chmod 644 ca.pem ./*.pem governance.* permissions.*
echo "$dir: $ca_state; issued: ${issued[*]:-none}; ${#added[@]} grant(s) added to permissions.p7s; ${#servers[@]} server(s), ${#nodes[@]} node(s), ${#readers[@]} reader(s) named${alt:+; management.pem for $alt}${management_clients[*]:+; management clients ${management_clients[*]}}"
