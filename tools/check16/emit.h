/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* emit.h - the output API of the 16-bit check: one text line per vector, same bytes on PC and AVR.
 */
#ifndef EMIT_H
#define EMIT_H

#include <stdbool.h>
#include <stdint.h>

/*
 * A vector file (vec_<module>.c) computes results and prints them with these
 * functions. Every vector is one line of lower-case hex tokens separated by
 * single spaces, ended by emit_end(); put the inputs first, then emit_sep(),
 * then the outputs, so a mismatch report shows what was fed in:
 *
 *     emit_i16(theta); emit_sep(); emit_i16(sc.sin); emit_i16(sc.cos); emit_end();
 *     -> "2000 | 5a82 5a82"
 *
 * emit_section("name") starts a named group ("# name" line); tools/check16/run
 * counts vectors per section and names the section and the vector number of
 * the first difference. Names: letters, digits, '_' and '/' only (the simavr
 * UART log turns control characters into '.', so the text must avoid them),
 * and keep lines under 200 characters (simavr splits longer ones).
 */
void emit_section(const char *name);
void emit_i16(int16_t v);      /* 4 hex digits, two's complement */
void emit_u16(uint16_t v);     /* 4 hex digits */
void emit_i32(int32_t v);      /* 8 hex digits, two's complement */
void emit_u32(uint32_t v);     /* 8 hex digits */
void emit_u8(uint8_t v);       /* 2 hex digits */
void emit_bool(bool v);        /* "0" or "1" */
void emit_sep(void);           /* "|" between inputs and outputs */
void emit_end(void);           /* end of one vector's line; counts it */
void emit_text(const char *s); /* a whole free-text line, not counted as a vector */
uint32_t emit_count(void);     /* vectors emitted so far */

/*
 * Deterministic inputs: xorshift32, identical on every compiler. Each
 * section should call vec_seed() with its own constant so that adding
 * vectors to one section does not shift the inputs of the others. Never
 * draw twice in one expression or one argument list: C leaves the order of
 * the two calls unspecified, and XC16 and gcc on the PC choose differently.
 */
void vec_seed(uint32_t seed);
uint32_t vec_rand_u32(void);
uint16_t vec_rand_u16(void);
int16_t vec_rand_i16(void);
/* Uniform in [lo, hi] (lo <= hi), by rejection-free modulo (bias is irrelevant here). */
int16_t vec_rand_between(int16_t lo, int16_t hi);

/* Hand-picked int16 edges: -32768, -32767, -16385, -16384, -1, 0, 1, 16383,
 * 16384, 32766, 32767. vec_edge_or_rand(k) returns edge k for k < VEC_N_EDGES
 * and a random value otherwise, so "for k in 0..n" covers edges first. */
#define VEC_N_EDGES 11U
extern const int16_t vec_edges[VEC_N_EDGES];
int16_t vec_edge_or_rand(uint32_t k);
/* For k < VEC_N_EDGES^2, writes edge pair k (every (edge, edge) pair, first
 * component major) to *a, *b and returns true; otherwise writes nothing and
 * returns false, so the caller draws its own random pair. */
bool vec_edge_pair(uint32_t k, int16_t *a, int16_t *b);

/*
 * Recorded input tables (e.g. an ADC frame sequence for vec_mc.c) must not
 * live in RAM on the AVR (8 KB; avr-gcc copies const data to RAM). Declare
 * them `static const int16_t name[] VEC_ROM = {...};` and read each element
 * with vec_rom_i16(&name[k]): flash (PROGMEM) on the AVR, plain const on the
 * PC. Keep one table under 32 KB (16-bit flash pointers on the AVR).
 */
#if defined(__AVR__)
#include <avr/pgmspace.h>
#define VEC_ROM PROGMEM
#else
#define VEC_ROM
#endif
int16_t vec_rom_i16(const int16_t *p);

/* platform.c: start the output, one output character (UART on the AVR,
 * stdout on the PC), and end the program once the output has left. */
void platform_init(void);
void emit_putc(char c);
void platform_exit(void);

#endif /* EMIT_H */
