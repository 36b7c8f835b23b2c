#!/bin/sh
# test_choosing_examples.sh — every console example of docs/choosing.md (the
# guide from a budget to a command) prints exactly what the guide shows,
# checked as README's are (test_readme_examples.sh).
README="$(pwd)/docs/choosing.md" MIN_EXAMPLES=6 exec sh "$(dirname "$0")/test_readme_examples.sh"
