#!/usr/bin/env bash
# Installs what is missing, builds, checks the layout rules, runs every gtest and rostest, and
# exits non-zero if any test fails or none ran. CI (.ci/run) calls exactly this.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

# The house rules the compiler does not check (stage order, no path outside the checkout).
/usr/bin/python3 "$ALEGO_ROOT/scripts/check_layout.py"

cd "$ALEGO_WS"
rm -rf build/test_results
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
echo "test: all $count tests passed"
