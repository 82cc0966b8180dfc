# Sourced by the bad-input scripts. expect_bad NAME PATTERN OUTPUT -- command...
# The command must exit with code 2, print a message matching PATTERN (extended regex, case
# insensitive) and leave neither OUTPUT nor OUTPUT.partial nor OUTPUT.checkpoint.h5 behind.
failures=0; passed=0
expect_bad() {
  local name=$1 pattern=$2 out=$3; shift 4
  local err rc
  err=$("$@" 2>&1 >/dev/null); rc=$?
  if [[ $rc -ne 2 ]]; then echo "FAIL $name: exit code $rc, expected 2 ($err)"; failures=$((failures+1)); return; fi
  if ! grep -qiE "$pattern" <<<"$err"; then echo "FAIL $name: message '$err' does not match /$pattern/"; failures=$((failures+1)); return; fi
  if [[ -e "$out" || -e "$out.partial" || -e "$out.checkpoint.h5" ]]; then echo "FAIL $name: output $out was left behind"; failures=$((failures+1)); return; fi
  echo "ok   $name: $err"; passed=$((passed+1))
}
