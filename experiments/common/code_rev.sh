#!/bin/sh
# code_rev.sh — the revision stamp of `make report`: the abbreviated commit
# that last changed the code or data the report is computed from (every path
# except reports/, tests/, .ci/, .gitignore and the Markdown documents), with
# "-dirty" when those paths differ from the last commit.  Committing
# regenerated reports (or tests, or docs) therefore does not change it.
# data/cost_model.tsv, which `make report` itself rewrites first (the
# cost_model experiment), does not make a run "-dirty": it is the report's
# output there, and the stamp names the code that produced it.
# Prints "unknown" outside a git checkout.
cd "$(dirname "$0")/../.." || exit 1
set -- . ':(exclude)reports' ':(exclude)tests' ':(exclude).ci' ':(exclude).gitignore' ':(exclude)*.md'
rev=$(git log -1 --format=%h --abbrev=12 -- "$@" 2>/dev/null) || rev=""
if [ -z "$rev" ]; then echo unknown; exit 0; fi
git diff --quiet HEAD -- "$@" ':(exclude)data/cost_model.tsv' 2>/dev/null || rev="$rev-dirty"
echo "$rev"
