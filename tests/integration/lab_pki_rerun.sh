#!/usr/bin/env bash
# scripts/make-lab-pki.sh run again on a lab's directory (the TLS recipe after the DDS Security
# one) never replaces the lab's CA, keys or certificates: the running nodes' certificates still
# verify against ca.pem, the permissions keep every grant; what is missing (the management
# certificate, a new participant) is added, signed by the existing CA. A participant named again
# with other permissions, a management certificate for other hosts, or a CA certificate without
# its key is refused with a message saying why, and nothing is written.
# Usage: lab_pki_rerun.sh (needs openssl only)
source "$(dirname "$0")/lib.sh" "$@"
pki_script=$(cd "$(dirname "$0")/../.." && pwd)/scripts/make-lab-pki.sh
lab=$tmp/lab

digests() { (cd "$lab" && sha256sum ./*.pem ./*.key governance.* permissions.*); }
verify() {  # verify CERT...: each signed by the lab's CA
  for cert in "$@"; do
    openssl verify -CAfile "$lab/ca.pem" "$lab/$cert" >/dev/null ||
      { echo "FAIL: $cert does not verify against the lab's ca.pem"; exit 1; }
  done
}
# refused WHAT ARGS...: the script exits non-zero, says WHAT, and leaves every file as it was.
refused() {
  local what=$1 before rc=0
  shift
  before=$(digests)
  bash "$pki_script" "$lab" "$@" >"$tmp/refused.txt" 2>&1 || rc=$?
  [ "$rc" -ne 0 ] || { echo "FAIL: '$*' was accepted"; cat "$tmp/refused.txt"; exit 1; }
  grep -q -- "$what" "$tmp/refused.txt" || { echo "FAIL: '$*' refused without '$what':"; cat "$tmp/refused.txt"; exit 1; }
  [ "$(digests)" == "$before" ] || { echo "FAIL: '$*' was refused but changed the lab's files"; exit 1; }
  echo "refused: $(head -1 "$tmp/refused.txt")"
}

# The DDS Security recipe, then the TLS recipe on the same directory.
bash "$pki_script" "$lab" --server netmc-server --node stage1-x:stage1.x --node stage1-y:stage1.y \
  --reader monitor >/dev/null
digests >"$tmp/first.sha256"
bash "$pki_script" "$lab" --server netmc-server --management 127.0.0.1
(cd "$lab" && sha256sum -c --quiet "$tmp/first.sha256") ||
  { echo "FAIL: the second run changed the lab's CA, keys, certificates, governance or permissions"; exit 1; }
verify netmc-server.pem stage1-x.pem stage1-y.pem monitor.pem management.pem
openssl x509 -in "$lab/management.pem" -noout -ext subjectAltName | grep -q "IP Address:127.0.0.1" ||
  { echo "FAIL: management.pem does not name 127.0.0.1"; exit 1; }
echo "second run: CA, keys, certificates, governance and permissions byte-identical; management.pem added"

# The same run once more changes nothing at all.
digests >"$tmp/second.sha256"
bash "$pki_script" "$lab" --server netmc-server --management 127.0.0.1 >/dev/null
(cd "$lab" && sha256sum -c --quiet "$tmp/second.sha256") || { echo "FAIL: a repeated run changed a file"; exit 1; }

# A new node is added: its certificate from the same CA, the old grants kept, permissions re-signed.
bash "$pki_script" "$lab" --server netmc-server --node stage1-z:stage1.z >/dev/null
grep -v permissions "$tmp/second.sha256" | (cd "$lab" && sha256sum -c --quiet) ||
  { echo "FAIL: adding a node changed an existing file other than the permissions"; exit 1; }
verify stage1-x.pem stage1-y.pem stage1-z.pem
for name in netmc-server stage1-x stage1-y monitor stage1-z; do
  grep -q "<grant name=\"$name\">" "$lab/permissions.xml" || { echo "FAIL: the permissions lost $name"; exit 1; }
done
openssl smime -verify -in "$lab/permissions.p7s" -CAfile "$lab/ca.pem" -out "$tmp/signed.xml" 2>/dev/null
openssl smime -verify -in "$lab/governance.p7s" -CAfile "$lab/ca.pem" -out /dev/null 2>/dev/null
grep -q '<grant name="stage1-z">' "$tmp/signed.xml" || { echo "FAIL: the signed permissions lack stage1-z"; exit 1; }
echo "a third node added: its certificate from the same CA, every grant kept, permissions signed by it"

refused "stage1-x: already in" --server netmc-server --node stage1-x:stage1.q
refused "management.pem" --server netmc-server --management 10.0.0.9
refused "monitor: already in" --server netmc-server --node monitor:stage1.m
cp -r "$lab" "$tmp/keyless" && rm "$tmp/keyless/ca.key"
lab=$tmp/keyless refused "ca.key" --server netmc-server --node stage2-x:stage2.x
echo "make-lab-pki.sh reruns keep the lab's CA, keys and certificates"
