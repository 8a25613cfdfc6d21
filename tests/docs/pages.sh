#!/usr/bin/env bash
# The documentation's shape: every page under docs/ (notes included) at most 600 lines,
# so that a page is a reference or a tutorial, not a notebook; and no code comment,
# example or reference page points outside the repository (a METHOD.md that is not in
# it: the paper's equations are in docs/method.md) or at the project's issue numbers
# (that history is git log's). Fails listing every offender.
#
#   bash tests/docs/pages.sh          (BAPD_SOURCE_DIR from ctest, else the repository)
set -uo pipefail
src="${BAPD_SOURCE_DIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}"
cd "$src" || exit 1
max_lines=600
failures=0
while IFS= read -r page; do
  lines=$(wc -l < "$page")
  if ((lines > max_lines)); then
    echo "FAIL $page: $lines lines, more than $max_lines (split it, or move measurements to docs/notes/)"
    failures=$((failures + 1))
  fi
done < <(find docs -name '*.md' | sort)
pointers=$(grep -rn "METHOD\.md\|issue [0-9]" src include examples docs/*.md)
if [ -n "$pointers" ]; then
  echo "FAIL a reference to METHOD.md or to an issue number (cite docs/method.md; history belongs in git log):"
  echo "$pointers" | sed 's/^/    /'
  failures=$((failures + 1))
fi
pages=$(find docs -name '*.md' | wc -l)
if ((failures)); then
  echo "docs.pages: $failures problem(s)"
  exit 1
fi
echo "docs.pages: $pages pages, none over $max_lines lines; no METHOD.md or issue numbers in src, include, examples, docs"
