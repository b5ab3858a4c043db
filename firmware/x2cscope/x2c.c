/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* x2c.c - the X2Cscope target's services and its whitelist (see x2c.h, x2c_vars.h). */
#include "x2c.h"

#include <stddef.h>

#include "motor.h"
#include "q15.h"

/* ---- the whitelist ------------------------------------------------------------- */

#if defined(X2C_READ_ONLY)
#define X2C_TUNE_FLAGS (X2C_ROW_READ | X2C_ROW_CHANNEL) /* the build switch: nothing writable */
#else
#define X2C_TUNE_FLAGS (X2C_ROW_READ | X2C_ROW_CHANNEL | X2C_ROW_TUNE)
#endif

#define X2C_MEMBER_SIZE(type, member) sizeof(((type *)0)->member)

/* Defined without a size: a row count other than X2C_ROWS conflicts with
 * the declaration and stops the build. */
const x2c_row_t x2c_rows[] = {
#define X2C_MOTOR_ROW(path, type, unit, fs)                                                        \
    {(uint16_t)offsetof(mc_t, path), (uint16_t)X2C_MEMBER_SIZE(mc_t, path), X2C_OBJ_MOTOR,         \
     X2C_ROW_READ | X2C_ROW_CHANNEL},
    X2C_MOTOR_VARS(X2C_MOTOR_ROW)
#undef X2C_MOTOR_ROW
#define X2C_TUNE_ROW(field, min, max, unit, fs)                                                    \
    {(uint16_t)offsetof(x2c_tune_t, field), 2U, X2C_OBJ_TUNE, X2C_TUNE_FLAGS},
        X2C_TUNABLES(X2C_TUNE_ROW)
#undef X2C_TUNE_ROW
#if X2C_SCOPE
            {0U, X2C_SCOPE_BYTES, X2C_OBJ_SCOPE, X2C_ROW_READ},
#endif
#define X2C_ID_ROW(field, type, unit, fs)                                                          \
    {(uint16_t)offsetof(mc_id_result_t, field), (uint16_t)X2C_MEMBER_SIZE(mc_id_result_t, field),  \
     X2C_OBJ_ID, X2C_ROW_READ},
    X2C_ID_VARS(X2C_ID_ROW)
#undef X2C_ID_ROW
};

/* The tunables' ranges, in row order. */
static const int16_t tune_min[] = {
#define X2C_TUNE_MIN(field, min, max, unit, fs) (int16_t)(min),
    X2C_TUNABLES(X2C_TUNE_MIN)
#undef X2C_TUNE_MIN
};
static const int16_t tune_max[] = {
#define X2C_TUNE_MAX(field, min, max, unit, fs) (int16_t)(max),
    X2C_TUNABLES(X2C_TUNE_MAX)
#undef X2C_TUNE_MAX
};

#if UINTPTR_MAX > 0xFFFFU
/* The PC: every object must fit its part of the window. */
Q15_STATIC_ASSERT(sizeof(x2c_tune_t) <= X2C_WINDOW_ID - X2C_WINDOW_TUNE, "tunables overlap");
Q15_STATIC_ASSERT(sizeof(mc_id_result_t) <= X2C_WINDOW_SCOPE - X2C_WINDOW_ID, "result overlaps");
Q15_STATIC_ASSERT(X2C_SCOPE_BYTES <= X2C_WINDOW_MOTOR - X2C_WINDOW_SCOPE, "buffer overlaps");
Q15_STATIC_ASSERT(sizeof(mc_t) <= 0x10000UL - X2C_WINDOW_MOTOR, "mc_t exceeds the window");
#endif
Q15_STATIC_ASSERT(X2C_SCOPE_BYTES <= X2C_ROW_SIZE_MAX, "the buffer's size exceeds a row's");
Q15_STATIC_ASSERT(X2C_OBJ_COUNT <= 4U, "a row's object is 2 bits");
Q15_STATIC_ASSERT((long)(MC_SPEED_FULLSCALE_RPM + 0.5) < 65536L,
                  "speed_ref_rpm's conversion divides by the full scale in 16 bits");
/* save parameter: 3 + state, nch, prescaler + 6 a channel + the trigger's 12 + its level */
Q15_STATIC_ASSERT(3U + 4U + 6U * X2C_SCOPE_CHANNELS + 12U + 4U <= X2C_REQUEST_MAX,
                  "the request buffer cannot hold a full scope configuration");
Q15_STATIC_ASSERT(X2C_RX_BYTES <= LNET_MAX_DATA, "a request buffer beyond a frame");
/* quiet_ms saturates at 255: a gap of 255 ms or more would never be reached */
Q15_STATIC_ASSERT(X2C_RX_GAP_MS >= 1U && X2C_RX_GAP_MS < 255U,
                  "X2C_RX_GAP_MS must be 1..254 ms (the inter-byte timeout, x2c.h)");

static const volatile uint8_t *obj_base(const x2c_t *x, uint8_t obj)
{
    switch (obj) {
        case X2C_OBJ_MOTOR:
            return (const volatile uint8_t *)(const volatile void *)motor_view();
        case X2C_OBJ_TUNE:
            return (const volatile uint8_t *)(const volatile void *)&x->tune;
        case X2C_OBJ_ID:
            return (const volatile uint8_t *)(const volatile void *)&x->id;
        default:
#if X2C_SCOPE
            return x->scope.buf;
#else
            return NULL; /* no row lies in it */
#endif
    }
}

uint16_t x2c_wire(const x2c_t *x, x2c_obj_t obj)
{
#if UINTPTR_MAX > 0xFFFFU
    static const uint16_t window[X2C_OBJ_COUNT] = {X2C_WINDOW_MOTOR, X2C_WINDOW_TUNE,
                                                   X2C_WINDOW_SCOPE, X2C_WINDOW_ID};
    (void)x;
    return window[obj];
#else
    return (uint16_t)(uintptr_t)obj_base(x, (uint8_t)obj);
#endif
}

/* The row that holds all of [addr, addr + n), n >= 1, with the pointer to
 * addr's byte; NULL if none does. Wire addresses are 16-bit (every object
 * lies below 0x10000 on the wire: the PC's window, the dsPIC's RAM), and
 * the comparison never forms addr + n, so nothing wraps. */
static const x2c_row_t *find_row(const x2c_t *x, uint16_t addr, uint16_t n,
                                 const volatile uint8_t **p)
{
    uint8_t i;
    for (i = 0; i < X2C_ROWS; i++) {
        const x2c_row_t *r = &x2c_rows[i];
        uint16_t start = (uint16_t)(x2c_wire(x, (x2c_obj_t)r->obj) + r->offset);
        if (addr >= start && n <= r->size && (uint16_t)(addr - start) <= r->size - n) {
            *p = obj_base(x, r->obj) + r->offset + (uint16_t)(addr - start);
            return r;
        }
    }
    return NULL;
}

/* The alignment of a 16-bit word on this platform: 2 on the dsPIC (a word
 * at an odd address is an address-error trap) and the PC, 1 on the AVR
 * that runs the 16-bit check. */
typedef struct {
    uint8_t c;
    uint16_t w;
} word_align_t;
#define X2C_WORD_ALIGN ((uint16_t)offsetof(word_align_t, w))

/* An access of n bytes of width w at addr: whole elements, aligned. */
static uint8_t access_check(uint16_t addr, uint16_t n, uint8_t w)
{
    if ((w != 1U && w != 2U && w != 4U) || n == 0U || n % w != 0U) {
        return X2C_ERR_FORMAT;
    }
    if (w > 1U && addr % X2C_WORD_ALIGN != 0U) {
        return X2C_ERR_FORMAT; /* a word at an odd address traps on the dsPIC */
    }
    return X2C_ERR_OK;
}

/* ---- the tunables ---------------------------------------------------------------- */

static int16_t get_i16(const uint8_t *p)
{
    uint16_t u = (uint16_t)((uint16_t)p[0] | (uint16_t)((uint16_t)p[1] << 8));
    return (u >= 0x8000U) ? (int16_t)(-(int16_t)(0xFFFFU - u) - 1) : (int16_t)u;
}

#if X2C_SCOPE /* the scope's configuration only */
static uint32_t get_u32(const uint8_t *p)
{
    return (uint32_t)p[0] | ((uint32_t)p[1] << 8) | ((uint32_t)p[2] << 16) | ((uint32_t)p[3] << 24);
}
#endif

static void put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)(v & 0xFFU);
    p[1] = (uint8_t)(v >> 8);
}

static void put_u32(uint8_t *p, uint32_t v)
{
    put_u16(p, (uint16_t)(v & 0xFFFFU));
    put_u16(p + 2, (uint16_t)(v >> 16));
}

static bool running(mc_state_t state)
{
    return state != MC_STATE_STOPPED && state != MC_STATE_FAULT;
}

/* The tunables as the motor has them now. */
static void tune_refresh(x2c_t *x)
{
    mc_status_t st;
    motor_status(&st);
    x->tune.cur_kp = motor_get_gain(MC_GAIN_CUR_KP);
    x->tune.cur_ki = motor_get_gain(MC_GAIN_CUR_KI);
    x->tune.spd_kp = motor_get_gain(MC_GAIN_SPD_KP);
    x->tune.spd_ki = motor_get_gain(MC_GAIN_SPD_KI);
    if (!(x->remote && mc_reference_held(&st, x->ref_seq_mine))) {
        x->remote = false; /* S3 or the pot took the reference back */
        x->tune.speed_ref_rpm = 0;
    }
    x->tune.run = running(st.state) ? 1 : 0;
    x->tune.identify = (st.state == MC_STATE_IDENTIFY) ? 1 : 0;
}

static uint8_t set_gain(mc_gain_t gain, int16_t v)
{
    return motor_set_gain(gain, v) ? X2C_ERR_OK : X2C_ERR_LIMIT;
}

static uint8_t set_speed(x2c_t *x, int16_t rpm)
{
    if (rpm == 0) {
        motor_request(MC_REQUEST_REF_POT);
        x->remote = false;
        return X2C_ERR_OK;
    }
    if (MC_TORQUE_MODE) {
        return X2C_ERR_STATE; /* no speed loop to set */
    }
    if (rpm < X2C_RPM_MIN) {
        return X2C_ERR_LIMIT;
    }
    {
        /* rpm * 32768 / fs, rounded, by the 32 / 16 divider: below fs the
         * quotient is below 2^15; from fs up it would not be, and is full
         * scale anyway */
        const uint16_t fs = (uint16_t)(MC_SPEED_FULLSCALE_RPM + 0.5);
        int16_t q = 32767;
        if ((uint16_t)rpm < fs) {
            q = (int16_t)q15_dsp_divud(((uint32_t)(uint16_t)rpm << 15) + fs / 2U, fs);
        }
        x->ref_seq_mine = motor_set_reference(q);
        x->remote = true;
        return X2C_ERR_OK;
    }
}

static uint8_t set_run(x2c_t *x, int16_t run)
{
    if (run == 0) {
        motor_request(MC_REQUEST_STOP);
        return X2C_ERR_OK;
    }
    if (x->may_start != NULL && !x->may_start(x->may_start_ctx)) {
        return X2C_ERR_STATE; /* the fault pin still holds a hardware fault */
    }
    motor_request(MC_REQUEST_START);
    return X2C_ERR_OK;
}

/* identify = 1: from STOPPED only (the core refuses any other state, and
 * so does the target, with its error); 0: a measurement going on stopped. */
static uint8_t set_identify(x2c_t *x, int16_t on)
{
    mc_status_t st;
    motor_status(&st);
    if (on == 0) {
        if (st.state == MC_STATE_IDENTIFY) {
            motor_request(MC_REQUEST_STOP);
        }
        return X2C_ERR_OK;
    }
    if (st.state != MC_STATE_STOPPED || (x->may_start != NULL && !x->may_start(x->may_start_ctx))) {
        return X2C_ERR_STATE;
    }
    motor_request(MC_REQUEST_IDENTIFY);
    return X2C_ERR_OK;
}

/* Applies tunable t = v, v in its range; the field keeps v when accepted. */
static uint8_t tune_apply(x2c_t *x, uint8_t t, int16_t v)
{
    uint8_t err;
    switch (t) {
        case X2C_TUNE_cur_kp:
            err = set_gain(MC_GAIN_CUR_KP, v);
            break;
        case X2C_TUNE_cur_ki:
            err = set_gain(MC_GAIN_CUR_KI, v);
            break;
        case X2C_TUNE_spd_kp:
            err = set_gain(MC_GAIN_SPD_KP, v);
            break;
        case X2C_TUNE_spd_ki:
            err = set_gain(MC_GAIN_SPD_KI, v);
            break;
        case X2C_TUNE_speed_ref_rpm:
            err = set_speed(x, v);
            break;
        case X2C_TUNE_run:
            err = set_run(x, v);
            break;
        default: /* X2C_TUNE_identify */
            err = set_identify(x, v);
            break;
    }
    if (err == X2C_ERR_OK) {
        /* every tunable is an int16 field (x2c_vars.h) */
        *(int16_t *)(void *)((uint8_t *)&x->tune + x2c_rows[X2C_MOTOR_ROWS + t].offset) = v;
    }
    return err;
}

/* ---- the services ------------------------------------------------------------------ *
 * Each gets the request in d[0 .. n-1] (d[0] the service), writes its reply
 * data after d[0] and d[1] (service and error, set by the caller) and
 * returns the error and, in *out, the reply's data bytes after those two.
 * Each checks everything before it changes anything. */

static uint8_t dsp_state(void)
{
    mc_status_t st;
    motor_status(&st);
    return running(st.state) ? X2C_DSP_POWER_ON : X2C_DSP_POWER_OFF;
}

static uint8_t svc_device_info(x2c_t *x, uint8_t *d, uint8_t n, uint8_t *out)
{
    static const char date_time[] = X2C_BUILD_DATE X2C_BUILD_TIME; /* "MmmDDYYYY" "HHMM" */
    uint8_t *r = &d[2];
    uint8_t i;
    (void)x;
    if (n != 1U) {
        return X2C_ERR_FORMAT;
    }
    put_u16(&r[0], X2C_MONITOR_VER);
    put_u16(&r[2], X2C_APP_VER);
    r[4] = LNET_MAX_DATA;
    put_u16(&r[5], X2C_PROCESSOR_ID);
    for (i = 0; i < 13U; i++) {
        r[7U + i] = (uint8_t)date_time[i];  /* monitor date and time */
        r[20U + i] = (uint8_t)date_time[i]; /* application date and time */
    }
    r[33] = dsp_state();
    put_u16(&r[34], 0U);  /* event type */
    put_u32(&r[36], 0UL); /* event id */
    put_u32(&r[40], 0UL); /* table address: no parameter table */
    *out = X2C_INFO_BYTES;
    return X2C_ERR_OK;
}

static uint8_t svc_get_state(x2c_t *x, uint8_t *d, uint8_t n, uint8_t *out)
{
    (void)x;
    if (n != 1U) {
        return X2C_ERR_FORMAT;
    }
    d[2] = dsp_state();
    *out = 1U;
    return X2C_ERR_OK;
}

/* 09 addr[2] count width */
static uint8_t svc_get_ram(x2c_t *x, uint8_t *d, uint8_t n, uint8_t *out)
{
    const volatile uint8_t *p;
    const x2c_row_t *row;
    uint16_t addr;
    uint8_t count, err;
    if (n != 5U) {
        return X2C_ERR_FORMAT;
    }
    addr = (uint16_t)((uint16_t)d[1] | (uint16_t)((uint16_t)d[2] << 8));
    count = d[3];
    err = access_check(addr, count, d[4]);
    if (err != X2C_ERR_OK) {
        return err;
    }
    if (count > X2C_READ_MAX) {
        return X2C_ERR_SIZE;
    }
    row = find_row(x, addr, count, &p);
    if (row == NULL) {
        return X2C_ERR_FORMAT;
    }
    if (row->obj == X2C_OBJ_TUNE) {
        tune_refresh(x);
    } else if (row->obj == X2C_OBJ_ID) {
        /* only here: the result's 64-bit conversions, not for every tunable's read */
        motor_identify_result(&x->id);
    }
    if (row->obj == X2C_OBJ_SCOPE) {
        x->body = p; /* sent from the buffer as it is (a client reads it stopped) */
    } else if (2U + count > X2C_RX_BYTES) {
        return X2C_ERR_SIZE; /* a variable is at most 4 bytes: not reached */
    } else if (row->obj == X2C_OBJ_MOTOR) {
        motor_copy(&d[2], p, count); /* at most 4 bytes (a variable), masked */
    } else {
        uint8_t i;
        for (i = 0; i < count; i++) {
            d[2U + i] = p[i];
        }
    }
    *out = count;
    return X2C_ERR_OK;
}

/* 0A addr[2] width data[n - 4] */
static uint8_t svc_put_ram(x2c_t *x, uint8_t *d, uint8_t n, uint8_t *out)
{
    const volatile uint8_t *p;
    const x2c_row_t *row;
    uint16_t addr;
    uint8_t count, err, t;
    int16_t v;
    (void)out;
    if (n < 5U) {
        return X2C_ERR_FORMAT;
    }
    addr = (uint16_t)((uint16_t)d[1] | (uint16_t)((uint16_t)d[2] << 8));
    count = (uint8_t)(n - 4U);
    err = access_check(addr, count, d[3]);
    if (err != X2C_ERR_OK) {
        return err;
    }
    row = find_row(x, addr, count, &p);
    if (row == NULL || (row->flags & X2C_ROW_TUNE) == 0U) {
        return X2C_ERR_FORMAT; /* not a tunable */
    }
    if (count != row->size || p != obj_base(x, row->obj) + row->offset) {
        return X2C_ERR_FORMAT; /* a tunable is written whole */
    }
    t = (uint8_t)(row - &x2c_rows[X2C_MOTOR_ROWS]);
    v = get_i16(&d[4]);
    if (v < tune_min[t] || v > tune_max[t]) {
        return X2C_ERR_LIMIT;
    }
    return tune_apply(x, t, v);
}

#if X2C_SCOPE
static uint8_t svc_load_param(x2c_t *x, uint8_t *d, uint8_t n, uint8_t *out)
{
    x2c_scope_run_t run;
    const x2c_scope_t *s = &x->scope;
    uint8_t *r = &d[2];
    if (n != 3U) {
        return X2C_ERR_FORMAT;
    }
    if (d[1] != X2C_PARAM_SCOPE || d[2] != 0U) {
        return X2C_ERR_PARAM;
    }
    motor_copy(&run, &s->run, (uint8_t)sizeof run); /* one consistent snapshot */
    r[0] = run.state;
    r[1] = s->cfg.nch;
    put_u16(&r[2], s->cfg.prescaler);
    put_u32(&r[4], run.wr);
    put_u32(&r[8], x2c_wire(x, X2C_OBJ_SCOPE));
    put_u32(&r[12], (uint32_t)s->cfg.delay);
    put_u32(&r[16], run.trig_pos);
    put_u32(&r[20], s->used);
    put_u32(&r[24], X2C_SCOPE_BYTES);
    r[28] = X2C_SCOPE_VERSION;
    *out = X2C_SCOPE_STATE_BYTES;
    return X2C_ERR_OK;
}

/* A scope channel or the trigger source: width bytes at addr, readable. */
static const volatile uint8_t *resolve(const x2c_t *x, uint8_t source_type, uint32_t addr,
                                       uint8_t width)
{
    const volatile uint8_t *p;
    const x2c_row_t *row;
    if (source_type != 0U || addr > 0xFFFFUL ||
        access_check((uint16_t)addr, width, width) != X2C_ERR_OK) {
        return NULL;
    }
    row = find_row(x, (uint16_t)addr, width, &p);
    return (row != NULL && (row->flags & X2C_ROW_CHANNEL) != 0U) ? p : NULL;
}

/* 12 01 00 state nch prescaler[2] {type addr[4] size}[nch]
 *   dtype type addr[4] level[dtype & 15] delay[4] edge [mode] */
static uint8_t svc_save_param(x2c_t *x, uint8_t *d, uint8_t n, uint8_t *out)
{
    x2c_scope_cfg_t cfg;
    const uint8_t *c = &d[3];
    uint8_t len, i, at, lsize, mode;
    uint32_t level;
    (void)out;
    if (n < 3U) {
        return X2C_ERR_FORMAT;
    }
    if (d[1] != X2C_PARAM_SCOPE || d[2] != 0U) {
        return X2C_ERR_PARAM;
    }
    len = (uint8_t)(n - 3U);
    if (len == 0U) {
        x2c_scope_stop(&x->scope); /* no channels: the scope stops */
        return X2C_ERR_OK;
    }
    if (len < 4U) {
        return X2C_ERR_FORMAT;
    }
    cfg.state = c[0];
    cfg.set.nch = c[1];
    cfg.set.prescaler = (uint16_t)((uint16_t)c[2] | (uint16_t)((uint16_t)c[3] << 8));
    if (cfg.state == X2C_SCOPE_IDLE) {
        x2c_scope_stop(&x->scope);
        return X2C_ERR_OK;
    }
    if (cfg.set.nch < 1U || cfg.set.nch > X2C_SCOPE_CHANNELS) {
        return X2C_ERR_LIMIT;
    }
    at = (uint8_t)(4U + 6U * cfg.set.nch); /* the trigger's dtype */
    if (len < at + 1U) {
        return X2C_ERR_FORMAT;
    }
    cfg.set.trig_dtype = c[at];
    lsize = (uint8_t)(cfg.set.trig_dtype & X2C_TRIG_SIZE);
    /* dtype type addr[4] level delay[4] edge, then the optional mode */
    if (lsize > 4U || (len != at + 11U + lsize && len != at + 12U + lsize)) {
        return X2C_ERR_FORMAT;
    }
    for (i = 0; i < cfg.set.nch; i++) {
        const uint8_t *ch = &c[4U + 6U * i];
        cfg.set.size[i] = ch[5];
        cfg.src[i] = resolve(x, ch[0], get_u32(&ch[1]), ch[5]);
        if (cfg.src[i] == NULL) {
            return X2C_ERR_FORMAT;
        }
    }
    for (; i < X2C_SCOPE_CHANNELS; i++) {
        cfg.src[i] = NULL;
        cfg.set.size[i] = 0;
    }
    level = 0;
    for (i = 0; i < lsize; i++) {
        level |= (uint32_t)c[at + 6U + i] << (8U * i);
    }
    cfg.set.delay = (int32_t)get_u32(&c[at + 6U + lsize]);
    if (c[at + 10U + lsize] > 1U) {
        return X2C_ERR_FORMAT; /* edge: 1 rising, 0 falling */
    }
    cfg.set.rising = c[at + 10U + lsize] == 1U;
    mode = (len == at + 12U + lsize) ? c[at + 11U + lsize] : 1U;
    cfg.set.trig_src = NULL;
    cfg.set.trig_level = 0;
    if (cfg.state == X2C_SCOPE_WAIT_TRIG && mode != 0U) {
        /* normal: the source must be a readable variable of the level's width */
        if (lsize == 0U) {
            return X2C_ERR_FORMAT;
        }
        cfg.set.trig_src = resolve(x, c[at + 1U], get_u32(&c[at + 2U]), lsize);
        if (cfg.set.trig_src == NULL) {
            return X2C_ERR_FORMAT;
        }
        cfg.set.trig_level = x2c_scope_key(level, cfg.set.trig_dtype);
    } else if (cfg.state == X2C_SCOPE_WAIT_TRIG) {
        cfg.set.trig_dtype =
            (uint8_t)((cfg.set.trig_dtype & (uint8_t)~X2C_TRIG_SIZE) | 1U); /* auto */
    }
    {
        uint8_t err = x2c_scope_check(&cfg);
        if (err != X2C_ERR_OK) {
            return err;
        }
    }
    x2c_scope_start(&x->scope, &cfg);
    return X2C_ERR_OK;
}
#endif /* X2C_SCOPE */

/* ---- the frame ---------------------------------------------------------------------- */

typedef uint8_t svc_fn_t(x2c_t *x, uint8_t *d, uint8_t n, uint8_t *out);

typedef struct {
    uint8_t id;
    svc_fn_t *run;
} svc_row_t;

static const svc_row_t services[] = {
    {X2C_SVC_DEVICE_INFO, svc_device_info}, {X2C_SVC_GET_STATE, svc_get_state},
    {X2C_SVC_GET_RAM, svc_get_ram},         {X2C_SVC_PUT_RAM, svc_put_ram},
#if X2C_SCOPE
    {X2C_SVC_LOAD_PARAM, svc_load_param},   {X2C_SVC_SAVE_PARAM, svc_save_param},
#endif
};

static void tally(uint16_t *c)
{
    if (*c < 0xFFFFU) {
        (*c)++;
    }
}

/* The reply: service and error in the request's buffer, then n bytes of
 * data after them there or, when the service set x->body, read from it. */
static void reply(x2c_t *x, uint8_t service, uint8_t err, uint8_t n)
{
    uint8_t size = (uint8_t)(2U + (err == X2C_ERR_OK ? n : 0U));
    x->rx.data[0] = service;
    x->rx.data[1] = err;
    tally(err == X2C_ERR_OK ? &x->answered : &x->refused);
    if (err == X2C_ERR_OK && x->body != NULL) {
        lnet_tx_start(&x->tx, LNET_NODE, x->rx.data, 2U, x->body, size);
    } else {
        lnet_tx_start(&x->tx, LNET_NODE, x->rx.data, size, NULL, size);
    }
    x->body = NULL;
}

static void dispatch(x2c_t *x)
{
    uint8_t n = x->rx.size;
    uint8_t service, i, out = 0, err = X2C_ERR_SERVICE;
    if (n == 0U) {
        reply(x, 0U, X2C_ERR_FORMAT, 0U);
        return;
    }
    service = x->rx.data[0];
    for (i = 0; i < sizeof services / sizeof services[0]; i++) {
        if (services[i].id == service) {
            err = services[i].run(x, x->rx.data, n, &out);
            break;
        }
    }
    reply(x, service, err, out);
}

void x2c_init(x2c_t *x)
{
    lnet_rx_init(&x->rx, x->rx_buf, (uint8_t)X2C_RX_BYTES);
    x->body = NULL;
    lnet_tx_init(&x->tx);
#if X2C_SCOPE
    x2c_scope_init(&x->scope);
#endif
    x->may_start = NULL;
    x->may_start_ctx = NULL;
    x->remote = false;
    x->ref_seq_mine = 0;
    x->quiet_ms = 0;
    x->answered = 0;
    x->refused = 0;
    tune_refresh(x);
    motor_identify_result(&x->id);
}

void x2c_set_start_guard(x2c_t *x, bool (*may_start)(void *ctx), void *ctx)
{
    x->may_start = may_start;
    x->may_start_ctx = ctx;
}

bool x2c_rx_ready(const x2c_t *x)
{
    return !lnet_tx_busy(&x->tx);
}

void x2c_rx_byte(x2c_t *x, uint8_t byte)
{
    if (lnet_tx_busy(&x->tx)) {
        return; /* the reply still needs the buffer: the caller ignored x2c_rx_ready */
    }
    x->quiet_ms = 0;
    switch (lnet_rx_byte(&x->rx, byte)) {
        case LNET_RX_FRAME:
            dispatch(x);
            break;
        case LNET_RX_BAD_CRC:
            reply(x, x->rx.size > 0U ? x->rx.data[0] : 0U, X2C_ERR_CHECKSUM, 0U);
            break;
        case LNET_RX_BAD_FORMAT:
            reply(x, 0U, X2C_ERR_FORMAT, 0U);
            break;
        case LNET_RX_TOO_LONG:
            reply(x, 0U, X2C_ERR_SIZE, 0U); /* longer than any request taken */
            break;
        default: /* LNET_RX_NONE */
            break;
    }
}

bool x2c_tx_byte(x2c_t *x, uint8_t *byte)
{
    return lnet_tx_next(&x->tx, byte);
}

void x2c_tick_1ms(x2c_t *x)
{
    if (lnet_tx_busy(&x->tx)) {
        x->quiet_ms = 0; /* nothing is taken while a reply goes out */
        return;
    }
    if (x->quiet_ms < 0xFFU) {
        x->quiet_ms++;
    }
    if (x->quiet_ms == X2C_RX_GAP_MS) {
        (void)lnet_rx_gap(&x->rx); /* the client left mid-request: its bytes go */
    }
}
