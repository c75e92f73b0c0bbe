#!/usr/bin/env bash
# Installs what is missing, builds, checks the layout rules, runs every gtest and rostest, and
# exits non-zero if any test fails or none ran. CI (.ci/run) calls this, then this with --sanitize.
#
#   scripts/test.sh --sanitize   the same tests in .ws_sanitize/, built with clang,
#       AddressSanitizer (leaks included) and UndefinedBehaviorSanitizer, then every fuzz target
#       of fuzz/ for ALEGO_FUZZ_SECONDS (20) from its seed corpus; also fails on any sanitizer
#       report or fuzz finding. docs/TESTING.md tells more.
set -euo pipefail

sanitize=0
if [ "${1:-}" = "--sanitize" ]; then
  sanitize=1
  shift
fi
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

# Packages that only the sanitizer and fuzz build needs (setup.sh installs the rest).
install_sanitizer_packages() {
  local missing=() package
  for package in clang libclang-rt-dev llvm; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$package")
    fi
  done
  ((${#missing[@]})) || return 0
  echo "test: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
}

if ((sanitize)); then
  install_sanitizer_packages
  export ALEGO_WS="$ROOT/.ws_sanitize"
  # setup.sh hands its arguments to catkin_make.
  set -- -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DALEGO_SANITIZE=ON \
    -DALEGO_FUZZ=ON "$@"
fi
source "$ROOT/scripts/setup.sh"

# The house rules the compiler does not check (stage order, no path outside the checkout).
/usr/bin/python3 "$ALEGO_ROOT/scripts/check_layout.py"

cd "$ALEGO_WS"
rm -rf build/test_results
if ((sanitize)); then
  # Every sanitized process (tests, the tools they run, the rostest nodes) writes its report to a
  # file here instead of stderr, so that a report from a child process fails the run too.
  SANITIZER_LOGS="$ALEGO_WS/sanitizer_logs"
  rm -rf "$SANITIZER_LOGS"
  mkdir -p "$SANITIZER_LOGS"
  export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:log_path=$SANITIZER_LOGS/asan"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:log_path=$SANITIZER_LOGS/ubsan"
  export LSAN_OPTIONS="suppressions=$ALEGO_ROOT/cmake/lsan.supp:print_suppressions=0"
  export ASAN_SYMBOLIZER_PATH=/usr/bin/llvm-symbolizer
fi
echo "test: building and running tests (log: $ALEGO_WS/test.log)"
# catkin_make run_tests exits 0 even when tests fail: its status only tells whether they built.
if ! catkin_make -DCATKIN_ENABLE_TESTING=ON run_tests -j2 >"$ALEGO_WS/test.log" 2>&1; then
  tail -n 80 "$ALEGO_WS/test.log"
  echo "test: tests failed to build or run (full log: $ALEGO_WS/test.log)" >&2
  exit 1
fi
grep -E "^\[ *(RUN|  FAILED|  PASSED) *\]|FAILURE|ERROR" "$ALEGO_WS/test.log" | grep -v "RUN" || true
results=$(catkin_test_results build/test_results --all 2>&1) || true
summary=$(echo "$results" | tail -n 1)
# catkin_test_results skips a result file it cannot parse (a crashed or truncated test): fail.
if echo "$results" | grep -q "^Skipping"; then
  echo "$results" | grep "^Skipping"
  echo "test: a test left an unreadable result file" >&2
  exit 1
fi
catkin_test_results build/test_results --verbose >/dev/null 2>&1 && status=0 || status=$?
echo "test: $summary"
count=$(echo "$summary" | sed -n 's/^Summary: \([0-9]*\) tests.*/\1/p')
if [ -z "$count" ] || [ "$count" -eq 0 ]; then
  echo "test: no test ran" >&2
  exit 1
fi
if [ "$status" -ne 0 ]; then
  catkin_test_results build/test_results --verbose 2>&1 | tail -n 60
  echo "test: FAILED" >&2
  exit 1
fi
if ((sanitize)); then
  if compgen -G "$SANITIZER_LOGS/*" >/dev/null; then
    for report in "$SANITIZER_LOGS"/*; do
      echo "--- $report"
      head -n 40 "$report"
    done
    echo "test: sanitizer reports above (all in $SANITIZER_LOGS)" >&2
    exit 1
  fi
  echo "test: all $count tests passed under ASan, LSan and UBSan"
  exec "$ALEGO_ROOT/fuzz/run_all.sh" "$ALEGO_BIN" "$ALEGO_WS/fuzz" "${ALEGO_FUZZ_SECONDS:-20}"
fi
echo "test: all $count tests passed"
