#!/bin/sh
# test_choosing_examples.sh — every console example of docs/choosing.md (the
# guide from a budget to a command) prints exactly what the guide shows,
# checked as README's are (test_readme_examples.sh), except that measured
# errors of float kernels may differ at rounding level (ERROR_LOOSE there).
README="$(pwd)/docs/choosing.md" LABEL=choosing.md MIN_EXAMPLES=6 ERROR_LOOSE=1 exec sh "$(dirname "$0")/test_readme_examples.sh"
