#!/usr/bin/env bash
# scripts/validation/report.py writes sections 1-4 of docs/validation.md and keeps the
# rest of the page: spliced with the page's own sections 1-4 the page comes back
# unchanged; spliced with new sections 1-4, those sections change, and the
# introduction, the hand-written 3.2 and 3.3 and sections 5 onwards stay word for word.
#   report_splice.sh        (ctest sets BAPD_SOURCE_DIR)
set -uo pipefail
cd "$BAPD_SOURCE_DIR/scripts/validation" || exit 1
/usr/bin/python3 - "$BAPD_SOURCE_DIR/docs/validation.md" <<'PY'
import sys
from report import splice, top_sections

page = open(sys.argv[1]).read().splitlines()
sections = top_sections(page)
failures = []
for number in (0, 1, 2, 3, 4, 5):
    if number not in sections:
        failures.append(f"docs/validation.md has no section {number}")
hand_3 = [i for i, line in enumerate(sections[3]) if line.startswith("### 3.2")]
if not hand_3:
    failures.append("section 3 has no '### 3.2'")
if failures:
    print("\n".join("FAIL " + f for f in failures)); sys.exit(1)
generated_3 = sections[3][:hand_3[0]]
own = sections[1] + sections[2] + generated_3 + sections[4]
if splice(page, own) != page:
    failures.append("the page spliced with its own sections 1-4 is not the page")
new = []
for number in (1, 2, 3, 4):
    new += [sections[number][0], "", f"generated section {number}", ""]
spliced = top_sections(splice(page, new))
for number in (1, 2, 4):
    if spliced[number] != [sections[number][0], "", f"generated section {number}", ""]:
        failures.append(f"section {number} is not the generated one")
if spliced[3][:4] != [sections[3][0], "", "generated section 3", ""] or spliced[3][4:] != sections[3][hand_3[0]:]:
    failures.append("section 3: the generated part replaced, 3.2 onwards kept: not so")
for number in sections:
    if number == 0 or number >= 5:
        if spliced.get(number) != sections[number]:
            failures.append(f"hand-written section {number} changed")
print("\n".join("FAIL " + f for f in failures) or "report.py splices sections 1-4 and keeps the rest")
sys.exit(1 if failures else 0)
PY
