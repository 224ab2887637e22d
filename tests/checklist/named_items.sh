#!/usr/bin/env bash
# Every item of a module's checklist in the checklist file (its section 6.x, items written
# **3601-CE-17**) has a GoogleTest whose name contains the item id with underscores (CE_17), in a
# test suite named after the module (Commands3601, Homing3601, ...): ids repeat across modules.
# A row of a table-driven test counts as a test of that name (see `tables` below).
# Usage: named_items.sh CHECKLISTS MODULE SECTION_HEADING NEXT_HEADING TESTS_DIR [PENDING]
# PENDING: item ids (e.g. "CE-I1 PI-07") of a part not written yet; they are listed, not failed.
# Exit 77 (ctest: skipped) when the checklist file is not beside the checkout.
set -euo pipefail
checklists=$1 module=$2 from=$3 to=$4 tests=$5 pending=${6:-}
[ -f "$checklists" ] || { echo "no checklist file at $checklists: skipped"; exit 77; }

items=$(sed -n "/^$from/,/^$to/p" "$checklists" | grep -oE "\*\*$module-[A-Z]+-[A-Z0-9]+\*\*" |
  tr -d '*' | sed "s/^$module-//" | sort -u)
[ -n "$items" ] || { echo "no $module items found between '$from' and '$to'"; exit 1; }
suite="[[:space:]]*[A-Za-z0-9_]*${module}[A-Za-z0-9_]*[[:space:]]*,"
names=$(grep -rhoE "TEST(_F|_P)?\\(${suite}[[:space:]]*[A-Za-z0-9_]+" "$tests" |
  sed -E 's/.*,[[:space:]]*//')
# Table-driven tests (tests/support/checklist_rows.hpp): in a file with a TEST_P of the module's
# suite, each row opens with its name, the test's name: {"CE_05_VpBelowVs", ...} or
# {.name = "CE_05_VpBelowVs", ...}.
tables=$(grep -rlE "TEST_P\\(${suite}" "$tests" || true)
if [ -n "$tables" ]; then
  rows=$(grep -hoE '\{[[:space:]]*(\.name[[:space:]]*=[[:space:]]*)?"[A-Z][A-Za-z0-9_]*"' $tables |
    sed -E 's/.*"(.*)"/\1/')
  names=$(printf '%s\n%s\n' "$names" "$rows")
fi

missing=0
for item in $items; do
  if [[ " $pending " == *" $item "* ]]; then
    echo "pending: $module-$item"
    continue
  fi
  key=${item//-/_}
  if ! grep -qE "(^|_)${key}(_|\$)" <<<"$names"; then
    echo "no test named after $module-$item"
    missing=$((missing + 1))
  fi
done
total=$(wc -w <<<"$items")
echo "$((total - missing)) of $total $module checklist items have a named test"
[ "$missing" -eq 0 ]
