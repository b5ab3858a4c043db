#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Copyright 2026 The open AN1078 authors
# test_firmware_build.sh - CTest checks of tools/firmware_build (make firmware).
#   no-xc16 <root>  without XC16: exactly one line on stderr naming XC16_DIR and the
#                   download page, nothing on stdout, exit status 2, no image;
#                   the same when XC16_DIR points to a directory without xc16-gcc.
#   print <root>    `make -n firmware` and `tools/firmware_build --print` print the
#                   compile / link / bin2hex lines with the facts sheet's flags.
#   fake <root>     with stand-in xc16-gcc / xc16-bin2hex that record their calls:
#                   every source compiled, one link, one bin2hex, the .hex in place;
#                   a compiler failure leaves no .hex behind.
#   mplabx <root>   the committed MPLAB X project (firmware/an1078.X) is what
#                   `tools/firmware_build --mplabx mclv hurst` writes (header items
#                   aside): same sources, include directories and defines as
#                   make firmware.
#   hostcc <root>   the same, with the host gcc standing in for xc16-gcc (XC16-only
#                   flags dropped, the SFR stand-in on the include path, strict
#                   warnings as errors): every source of the image compiles and the
#                   objects link into ONE program (one main, the ISR, the core, no
#                   missing or duplicate symbol); run for 1 s it must still be in
#                   its main loop (killed by the timeout), not crashed in hal_init.
set -u
mode=$1
root=$2
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
clean_env=(env -u XC16_DIR -u MAKEFLAGS -u MFLAGS -u MAKELEVEL)

case "$mode" in
no-xc16)
  for variant in unset bogus; do
    if [ $variant = unset ]; then
      envset=("${clean_env[@]}" PATH=/usr/bin:/bin FIRMWARE_OUT="$tmp/out")
    else
      envset=("${clean_env[@]}" PATH=/usr/bin:/bin FIRMWARE_OUT="$tmp/out" XC16_DIR="$tmp/nowhere")
    fi
    "${envset[@]}" "$root/tools/firmware_build" mclv hurst >"$tmp/stdout" 2>"$tmp/stderr"
    rc=$?
    echo "measured: XC16_DIR $variant: exit $rc, stderr $(wc -l <"$tmp/stderr") line(s): $(cat "$tmp/stderr")"
    [ $rc -eq 2 ] || fail "exit status $rc, expected 2"
    [ "$(wc -l <"$tmp/stderr")" -eq 1 ] || fail "stderr is not one line"
    [ ! -s "$tmp/stdout" ] || fail "stdout not empty"
    grep -q "XC16 not found" "$tmp/stderr" || fail "no 'XC16 not found'"
    grep -q "XC16_DIR" "$tmp/stderr" || fail "does not name XC16_DIR"
    grep -q "https://www.microchip.com/mplab/compilers" "$tmp/stderr" || fail "no download address"
    [ ! -e "$tmp/out/mclv.hex" ] || fail "an image was written"
  done
  # Through make, as CI runs it.
  "${clean_env[@]}" PATH=/usr/bin:/bin make -s -C "$root" firmware BUILD="$tmp/b" >"$tmp/stdout" 2>"$tmp/stderr"
  rc=$?
  echo "measured: make firmware: exit $rc, stderr: $(head -1 "$tmp/stderr")"
  [ $rc -ne 0 ] || fail "make firmware succeeded without XC16"
  grep -q "XC16 not found" "$tmp/stderr" || fail "make firmware: no 'XC16 not found'"
  ;;
print)
  check_lines() { # check_lines <file> <label>
    local f=$1 n_cc n_src
    n_src=$(cd "$root" && ls foc/*.c smc_estimator/*.c firmware/*.c firmware/x2cscope/*.c hal/dspic33f/*.c 2>/dev/null | wc -l)
    n_cc=$(grep -c -- ' -c ' "$f")
    echo "measured: $2: $n_cc compile lines for $n_src sources, $(grep -c 'xc16-bin2hex' "$f") bin2hex line(s)"
    [ "$n_cc" -eq "$n_src" ] || fail "$2: $n_cc compile lines, $n_src sources"
    [ "$(grep -- ' -c ' "$f" | grep -cE -- '-mcpu=33FJ32MC204 -omf=elf -O2 -g -fno-short-double')" -eq "$n_cc" ] ||
      fail "$2: a compile line lacks -mcpu=33FJ32MC204 -omf=elf -O2 -g -fno-short-double"
    # every file without the block copies; the interrupt's path with -O2's inlining, the
    # cold files without the small functions' (tools/firmware_build, "Code size")
    [ "$(grep -- ' -c ' "$f" | grep -c -- ' -fno-reorder-blocks ')" -eq "$n_cc" ] ||
      fail "$2: a compile line lacks -fno-reorder-blocks"
    grep -- ' -c firmware/mc.c ' "$f" | grep -q -- ' -fno-inline-small-functions ' &&
      fail "$2: mc.c, the interrupt's path, without -O2's inlining"
    grep -- ' -c hal/dspic33f/hal_isr.c ' "$f" | grep -q -- ' -fno-inline-small-functions ' &&
      fail "$2: hal_isr.c without -O2's inlining"
    grep -- ' -c firmware/app.c ' "$f" | grep -q -- ' -fno-inline-small-functions -fno-tree-ch -fno-tree-pre ' ||
      fail "$2: app.c without the cold files' flags"
    [ "$(grep -- ' -c ' "$f" | grep -c -- '-DMC_BOARD_MCLV -DMC_MOTOR_HURST')" -eq "$n_cc" ] ||
      fail "$2: a compile line lacks the board/motor defines"
    grep -q -- ' -c hal/dspic33f/hal_isr.c ' "$f" || fail "$2: hal_isr.c not compiled"
    grep -- '--script=p33FJ32MC204.gld' "$f" | grep -q -- '-mcpu=33FJ32MC204 -omf=elf' ||
      fail "$2: no link line with the device linker script"
    # a function no image calls is not linked: one section a function, and the linker drops the unused
    [ "$(grep -- ' -c ' "$f" | grep -c -- ' -ffunction-sections ')" -eq "$n_cc" ] ||
      fail "$2: a compile line lacks -ffunction-sections"
    grep -- '--script=p33FJ32MC204.gld' "$f" | grep -q -- ',--gc-sections,' ||
      fail "$2: the link line does not remove unused sections (--gc-sections)"
    grep -q -- 'xc16-bin2hex .*mclv.elf -a -omf=elf' "$f" || fail "$2: no xc16-bin2hex line"
  }
  "${clean_env[@]}" PATH=/usr/bin:/bin "$root/tools/firmware_build" --print mclv hurst >"$tmp/print" ||
    fail "--print exited non-zero"
  check_lines "$tmp/print" "firmware_build --print"
  "${clean_env[@]}" PATH=/usr/bin:/bin make -s -n -C "$root" firmware >"$tmp/maken" 2>&1 ||
    fail "make -n firmware exited non-zero"
  check_lines "$tmp/maken" "make -n firmware"
  [ ! -e "$root/build/firmware/mclv.tmp" ] || fail "--print created files"
  ;;
fake)
  mkdir -p "$tmp/xc16/bin"
  cat >"$tmp/xc16/bin/xc16-gcc" <<'EOS'
#!/bin/sh
echo "xc16-gcc $*" >>"$FAKE_LOG"
out=""; prev=""
for a in "$@"; do [ "$prev" = "-o" ] && out=$a; prev=$a; done
case " $* " in *" $FAKE_FAIL_ON "*) exit 1 ;; esac
[ -n "$out" ] && : >"$out"
exit 0
EOS
  cat >"$tmp/xc16/bin/xc16-bin2hex" <<'EOS'
#!/bin/sh
echo "xc16-bin2hex $*" >>"$FAKE_LOG"
echo ":00000001FF" >"${1%.elf}.hex"
EOS
  chmod +x "$tmp/xc16/bin/"*
  run() {
    "${clean_env[@]}" XC16_DIR="$tmp/xc16" FAKE_LOG="$tmp/log" FAKE_FAIL_ON="$1" \
      FIRMWARE_OUT="$tmp/out" "$root/tools/firmware_build" mclv hurst >"$tmp/stdout" 2>&1
  }
  : >"$tmp/log"
  run "no-such-file" || { cat "$tmp/stdout"; fail "fake build failed"; }
  n_src=$(cd "$root" && ls foc/*.c smc_estimator/*.c firmware/*.c firmware/x2cscope/*.c hal/dspic33f/*.c 2>/dev/null | wc -l)
  echo "measured: fake XC16: $(grep -c ' -c ' "$tmp/log") compiles ($n_src sources), $(grep -c 'script=' "$tmp/log") link, $(grep -c bin2hex "$tmp/log") bin2hex"
  [ "$(grep -c ' -c ' "$tmp/log")" -eq "$n_src" ] || fail "not every source compiled"
  [ "$(grep -c 'script=p33FJ32MC204.gld' "$tmp/log")" -eq 1 ] || fail "not one link"
  [ -s "$tmp/out/mclv.hex" ] || fail "no hex"
  [ -z "$(ls -A "$tmp/out" | grep '^\.mclv')" ] || fail "scratch directory left behind"
  # A compile failure: no image, not even the previous one.
  : >"$tmp/log"
  if run "hal/dspic33f/hal_isr.c"; then fail "build succeeded with a failing compile"; fi
  [ ! -e "$tmp/out/mclv.hex" ] || fail "a hex survived a failed build"
  grep -q "script=" "$tmp/log" && fail "linked after a failed compile"
  echo "measured: failed compile -> exit non-zero, no mclv.hex"
  ;;
mplabx)
  committed=$root/firmware/an1078.X/nbproject/configurations.xml
  [ -f "$committed" ] || fail "no $committed"
  [ -f "$root/firmware/an1078.X/nbproject/project.xml" ] || fail "no project.xml"
  "${clean_env[@]}" MPLABX_PROJECT_DIR="$tmp/p" "$root/tools/firmware_build" --mplabx mclv hurst >/dev/null ||
    fail "--mplabx failed"
  # Headers are listed for browsing only (the include directories are what
  # compiles), so a new header does not make the project stale; sources do.
  if ! diff -u <(grep -v '\.h</itemPath>' "$committed") \
      <(grep -v '\.h</itemPath>' "$tmp/p/nbproject/configurations.xml"); then
    fail "firmware/an1078.X is out of date: run tools/firmware_build --mplabx mclv hurst"
  fi
  n_src=$(cd "$root" && ls foc/*.c smc_estimator/*.c firmware/*.c firmware/x2cscope/*.c hal/dspic33f/*.c 2>/dev/null | wc -l)
  n_item=$(grep -c '<itemPath>\.\./\.\./.*\.c</itemPath>' "$committed")
  echo "measured: MPLAB X project: $n_item source items for $n_src sources"
  [ "$n_item" -eq "$n_src" ] || fail "project lists $n_item sources, the image has $n_src"
  grep -q '<targetDevice>dsPIC33FJ32MC204</targetDevice>' "$committed" || fail "device"
  grep -q '<languageToolchain>XC16</languageToolchain>' "$committed" || fail "toolchain"
  grep -q 'key="output-file-format" value="elf"' "$committed" || fail "elf"
  # The IDE build gets the flags make firmware compiles with: the dialect
  # and 64-bit double have no MPLAB X property, they go in appendMe (C30 and
  # C30-LD), and the stack guard's key is oXC16ld-stackguard.
  cc_line=$("${clean_env[@]}" "$root/tools/firmware_build" --print mclv hurst | grep ' -c ' | head -1)
  for flag in -fno-short-double -std=gnu99; do
    case " $cc_line " in *" $flag "*) ;; *) fail "make firmware lacks $flag" ;; esac
    [ "$(grep -c "<appendMe value=\"[^\"]*$flag" "$committed")" -eq "$(grep -c '<appendMe ' "$committed")" ] ||
      fail "the MPLAB X project does not append $flag in every appendMe (C30, C30-LD, the cold files)"
  done
  n_cold=$(grep -c '<item path=' "$committed")
  [ "$(grep -c '<appendMe value="[^"]* -fno-reorder-blocks' "$committed")" -eq $((n_cold + 1)) ] ||
    fail "the MPLAB X project does not compile every file with -fno-reorder-blocks"
  [ "$(grep -c '<appendMe value="[^"]* -fno-inline-small-functions -fno-tree-ch -fno-tree-pre"' "$committed")" -eq "$n_cold" ] ||
    fail "the MPLAB X project's cold files lack their flags"
  echo "measured: MPLAB X project: $n_cold cold files with their own flags"
  grep -q 'key="oXC16ld-stackguard" value="16"' "$committed" || fail "stack guard key"
  grep -q 'key="fno-short-double"' "$committed" && fail "fno-short-double is no MPLAB X key"
  echo "measured: MPLAB X appends -fno-short-double -std=gnu99 to the compiler and the linker"
  grep -q 'value="MC_BOARD_MCLV;MC_MOTOR_HURST;MC_MOTOR_HEADER=&quot;motors/motor_hurst.h&quot;"' "$committed" ||
    fail "defines differ from make firmware"
  ;;
hostcc)
  mkdir -p "$tmp/xc16/bin"
  gcc -std=c99 -c "$root/test/support/sfr/sfr_standin.c" -I"$root/test/support/sfr" -o "$tmp/sfr.o" ||
    fail "stand-in does not compile"
  cat >"$tmp/xc16/bin/xc16-gcc" <<'EOS'
#!/usr/bin/env bash
args=(); link=1
for a in "$@"; do
  case "$a" in
    -mcpu=*|-omf=*|-msmart-io=*|-msfr-warn=*|-fno-short-double|-Wl,--script=*) ;;
    -c) link=0; args+=("$a") ;;
    *) args+=("$a") ;;
  esac
done
if [ $link -eq 1 ]; then
  exec gcc "${args[@]}" "$FAKE_SFR_OBJ" -lm
fi
exec gcc -Werror -Wconversion -Wsign-conversion -Wshadow -I"$FAKE_ROOT/test/support/sfr" "${args[@]}"
EOS
  cat >"$tmp/xc16/bin/xc16-bin2hex" <<'EOS'
#!/bin/sh
echo ":00000001FF" >"${1%.elf}.hex"
EOS
  chmod +x "$tmp/xc16/bin/"*
  "${clean_env[@]}" XC16_DIR="$tmp/xc16" FAKE_SFR_OBJ="$tmp/sfr.o" FAKE_ROOT="$root" \
    FIRMWARE_OUT="$tmp/out" "$root/tools/firmware_build" mclv hurst >"$tmp/stdout" 2>&1 ||
    { tail -30 "$tmp/stdout"; fail "the image does not compile or link with the host compiler"; }
  [ -s "$tmp/out/mclv.hex" ] || fail "no hex"
  nm "$tmp/out/mclv.elf" | grep -q ' T _ADC1Interrupt$' || fail "no _ADC1Interrupt in the image"
  nm "$tmp/out/mclv.elf" | grep -q ' T main$' || fail "no main in the image"
  nm "$tmp/out/mclv.elf" | grep -q ' T x2c_scope_sample$' || fail "no X2Cscope target in the image"
  (cd "$root" && gcc -std=c99 -Wall -Wextra -Werror -Wconversion -Wsign-conversion -Wshadow \
    -DAPP_NO_X2CSCOPE -DMC_BOARD_MCLV -DMC_MOTOR_HURST -Ifoc -Ismc_estimator -Ifirmware \
    -c firmware/main.c -o "$tmp/main_nox2c.o") || fail "main.c does not compile with -DAPP_NO_X2CSCOPE"
  timeout 1 "$tmp/out/mclv.elf" >/dev/null 2>&1
  rc=$?
  echo "measured: host-compiled image: $(grep -c ' -c ' "$tmp/stdout") objects linked, run 1 s -> exit $rc (124 = still looping)"
  [ $rc -eq 124 ] || fail "the image exited (status $rc) instead of looping"
  # The MCHV image is refused while its pin conflict (S3 on RB8 = FLTA1?)
  # is unresolved, with the message saying what to check; the one constant
  # HAL_MCHV_PINS_CONFIRMED lets it build.
  if "${clean_env[@]}" XC16_DIR="$tmp/xc16" FAKE_SFR_OBJ="$tmp/sfr.o" FAKE_ROOT="$root" \
    FIRMWARE_OUT="$tmp/out_mchv" "$root/tools/firmware_build" mchv hispeed >"$tmp/mchv" 2>&1; then
    fail "an MCHV image was built with its pin conflict unresolved"
  fi
  grep -q 'MCHV build refused: push-button S3 may share RB8 with the fault input FLTA1' "$tmp/mchv" ||
    { tail -5 "$tmp/mchv"; fail "the MCHV refusal does not say what to check"; }
  [ ! -e "$tmp/out_mchv/mchv.hex" ] || fail "a refused MCHV build left an image"
  "${clean_env[@]}" XC16_DIR="$tmp/xc16" FAKE_SFR_OBJ="$tmp/sfr.o" FAKE_ROOT="$root" \
    XC16_CFLAGS=-DHAL_MCHV_PINS_CONFIRMED=1 FIRMWARE_OUT="$tmp/out_mchv" \
    "$root/tools/firmware_build" mchv hispeed >"$tmp/mchv" 2>&1 ||
    { tail -20 "$tmp/mchv"; fail "the MCHV image does not build once its pins are confirmed"; }
  echo "measured: MCHV image refused until HAL_MCHV_PINS_CONFIRMED=1, then built"
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "ok"
