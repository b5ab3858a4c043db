/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* emit.c - hex line output and the deterministic input generator of the 16-bit check. */
#include "emit.h"

static uint32_t vectors;
static bool line_open;
static uint32_t rng = 1U;

static void put_hex(uint32_t v, uint8_t digits)
{
    static const char hex[] = "0123456789abcdef";
    if (line_open) {
        emit_putc(' ');
    }
    line_open = true;
    while (digits > 0U) {
        digits--;
        emit_putc(hex[(v >> (4U * digits)) & 0xFU]);
    }
}

static void put_str(const char *s)
{
    while (*s != '\0') {
        emit_putc(*s);
        s++;
    }
}

void emit_section(const char *name)
{
    if (line_open) {
        emit_putc('\n');
        line_open = false;
    }
    put_str("# ");
    put_str(name);
    emit_putc('\n');
}

void emit_text(const char *s)
{
    if (line_open) {
        emit_putc('\n');
        line_open = false;
    }
    put_str(s);
    emit_putc('\n');
}

void emit_i16(int16_t v)
{
    put_hex((uint16_t)v, 4U);
}

void emit_u16(uint16_t v)
{
    put_hex(v, 4U);
}

void emit_i32(int32_t v)
{
    put_hex((uint32_t)v, 8U);
}

void emit_u32(uint32_t v)
{
    put_hex(v, 8U);
}

void emit_u8(uint8_t v)
{
    put_hex(v, 2U);
}

void emit_bool(bool v)
{
    put_hex(v ? 1U : 0U, 1U);
}

void emit_sep(void)
{
    if (line_open) {
        emit_putc(' ');
    }
    emit_putc('|');
    line_open = true;
}

void emit_end(void)
{
    emit_putc('\n');
    line_open = false;
    vectors++;
}

uint32_t emit_count(void)
{
    return vectors;
}

void vec_seed(uint32_t seed)
{
    rng = (seed != 0U) ? seed : 0x9E3779B9UL;
}

uint32_t vec_rand_u32(void)
{
    uint32_t x = rng;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    rng = x;
    return x;
}

uint16_t vec_rand_u16(void)
{
    return (uint16_t)(vec_rand_u32() >> 16);
}

int16_t vec_rand_i16(void)
{
    return (int16_t)vec_rand_u16();
}

int16_t vec_rand_between(int16_t lo, int16_t hi)
{
    uint32_t span = (uint32_t)((int32_t)hi - (int32_t)lo) + 1U;
    return (int16_t)((int32_t)lo + (int32_t)(vec_rand_u32() % span));
}

const int16_t vec_edges[VEC_N_EDGES] = {-32768, -32767, -16385, -16384, -1,   0,
                                        1,      16383,  16384,  32766,  32767};

int16_t vec_edge_or_rand(uint32_t k)
{
    return (k < VEC_N_EDGES) ? vec_edges[k] : vec_rand_i16();
}

bool vec_edge_pair(uint32_t k, int16_t *a, int16_t *b)
{
    if (k >= VEC_N_EDGES * VEC_N_EDGES) {
        return false;
    }
    *a = vec_edges[k / VEC_N_EDGES];
    *b = vec_edges[k % VEC_N_EDGES];
    return true;
}

int16_t vec_rom_i16(const int16_t *p)
{
#if defined(__AVR__)
    return (int16_t)pgm_read_word(p);
#else
    return *p;
#endif
}
