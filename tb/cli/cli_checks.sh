# SPDX-License-Identifier: Apache-2.0
# Shared by the CLI check scripts (sourced): a temporary directory, pass/fail counters,
# expect_error and json_field. The caller sets BIN and SRC first and ends by printing
# the counts and exiting non-zero when a check failed.
set -u
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
fails=0 passes=0
pass() { passes=$((passes + 1)); }
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# expect_error NAME PATTERN -- command...: non-zero exit, no crash, stderr matching PATTERN.
expect_error() {
  local name="$1" pattern="$2"; shift 3
  local out rc
  out="$("$@" 2>&1 >/dev/null)"; rc=$?
  if [ $rc -eq 0 ]; then fail "$name: exit 0, expected an error"; return; fi
  if [ $rc -ge 128 ]; then fail "$name: crashed (rc $rc): $out"; return; fi
  if ! grep -Eq -- "$pattern" <<<"$out"; then fail "$name: error '$out' does not match '$pattern'"; return; fi
  pass
}
json_field() { /usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$1" "$2"; }
