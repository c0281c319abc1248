#!/usr/bin/env bash
# Checks that keep the docs true to the tree: docs/architecture.md names every header of the
# libraries (scenarios/ and all its folders), and nothing cites a document outside the
# repository (the repository speaks only of itself: docs/ pages and the paper by its title), and
# no test name that CTest would split.
# Run by CTest from the source root.
set -u
cd "$(dirname "$0")/.."
status=0
for header in sim/*.hpp ranks/*.hpp net/*.hpp protocols/*.hpp agents/*.hpp $(find scenarios -name '*.hpp' | sort); do
  if ! grep -q "$(basename "$header")" docs/architecture.md; then
    echo "docs/architecture.md does not name $header"
    status=1
  fi
done
# Citations of documents that are not in the repository.
# (Spelled with bracket classes, so that this file does not cite them itself.)
pattern='SPE[C] §|STYL[E] habit|\(STYL[E][):]|share[d]/peers|share[d]/seed'
if git ls-files >/dev/null 2>&1; then files=$(git ls-files | grep -v '^LICENSE$' | grep -v '^tests/check_repository.sh$'); else files=$(find . -type f -not -path './build/*' -not -path './.git/*'); fi
hits=$(echo "$files" | xargs grep -nIE "$pattern" 2>/dev/null || true)
if [ -n "$hits" ]; then
  echo "citations of documents outside the repository:"
  echo "$hits"
  status=1
fi
# A test name with a semicolon is split in two by CTest's list handling: two tests that fail.
hits=$(grep -rnE 'TEST_CASE\("[^"]*;' tests 2>/dev/null || true)
if [ -n "$hits" ]; then
  echo "test names with a semicolon (CTest splits them):"
  echo "$hits"
  status=1
fi
if [ "$status" -eq 0 ]; then echo "repository checks: ok"; fi
exit "$status"
