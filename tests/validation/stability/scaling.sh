#!/usr/bin/env bash
# Scaling: no hidden absolute tolerance. scaling.py runs a small plate at
# lengths x 1000, moduli x 1000 and both x 0.001 and compares the dimensionless
# histories, steps and static holds with the base scene.
set -uo pipefail
exec python3 "$BAPD_SOURCE_DIR/tests/validation/stability/scaling.py"
