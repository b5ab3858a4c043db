#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# layers.sh - the include graph has no edge running up (docs/architecture.md).
#
# Usage: test/layers.sh <repo root> <C compiler>
#
# Every .c and .h of a layer is run through the compiler's -MM with every
# source folder on the include path, so that an include of a higher layer's
# header, by name or by a relative path, resolves and shows up as an edge.
# Each layer may depend on the folders listed for it, nothing else:
#   boards/         boards/
#   foc/            foc/
#   smc_estimator/  smc_estimator/ foc/
#   hal/            hal/ boards/ foc/ (q15.h), and the device header (on the
#                   PC: test/support/sfr, the stand-in for XC16's <xc.h>)
#   firmware/       firmware/ hal/hal.h hal/hal_frame.h boards/ smc_estimator/ foc/
# Prints one line per upward edge and exits 1 if there is any.
set -u
root=${1:?repo root}
cc=${2:-cc}
cd "$root" || exit 2
inc=(-Iboards -Ifoc -Ismc_estimator -Ifirmware -Ihal -Ihal/dspic33f -Itest/support/sfr)
defs=(-DMC_BOARD_MCLV -DMC_MOTOR_HURST '-DMC_MOTOR_HEADER="motors/motor_hurst.h"' -DHAL_MCHV_PINS_CONFIRMED=1)

allowed() { # allowed <layer> <dependency path, repo-relative>
  case "$1:$2" in
    boards:boards/*) return 0 ;;
    foc:foc/*) return 0 ;;
    smc_estimator:smc_estimator/* | smc_estimator:foc/*) return 0 ;;
    hal:hal/* | hal:boards/* | hal:foc/* | hal:test/support/sfr/*) return 0 ;;
    firmware:firmware/* | firmware:hal/hal.h | firmware:hal/hal_frame.h) return 0 ;;
    firmware:boards/* | firmware:smc_estimator/* | firmware:foc/*) return 0 ;;
  esac
  return 1
}

bad=0
files=0
for layer in boards foc smc_estimator hal firmware; do
  while IFS= read -r f; do
    files=$((files + 1))
    deps=$("$cc" -MM -std=c99 -x c "${inc[@]}" "${defs[@]}" "$f" 2>&1) || {
      echo "layers: $f: the compiler failed: $(echo "$deps" | head -1)"
      bad=1
      continue
    }
    # one dependency per word after the target; paths normalised to the repo
    for d in $(echo "$deps" | sed -e 's/\\$//' -e 's/^[^:]*://'); do
      p=$(realpath -m --relative-to="$root" "$d")
      [ "$p" = "$(realpath -m --relative-to="$root" "$f")" ] && continue
      if ! allowed "$layer" "$p"; then
        echo "layers: $f -> $p: $layer/ may not include it"
        bad=1
      fi
    done
  done < <(find "$layer" -path '*/an1078.X' -prune -o -type f \( -name '*.c' -o -name '*.h' \) -print |
    LC_ALL=C sort)
done
[ $bad -eq 0 ] && echo "layers: $files files, no edge running up"
exit $bad
