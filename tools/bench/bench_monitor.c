/* bench_monitor.c - instruction count of the live data monitor: the ISR recorder and the main-loop
 * parser. */
/* bench-requires: firmware/mc.c firmware/monitor/monitor.c tools/sim/sim_mailbox.c */
/* bench-symbols: monitor_init monitor_sample monitor_rx_byte monitor_poll */
#include "bench.h"

#include "mc.h"
#include "monitor.h"
#include "../sim/sim_mailbox.h"

/*
 * The ISR side: monitor_sample() once per PWM period, after mc_step().
 *   stopped          the cost every period while nothing records;
 *   4ch_every_period decimation 1, four channels: every call takes a sample
 *                    (the worst case: one mc_status copy + four stores);
 *   4ch_decim10      decimation 10: the mean a realistic stream costs.
 * The main-loop side: monitor_rx_byte() per received byte (valid frames),
 * monitor_poll() while a stream is being sent (one DATA frame per call when
 * data is waiting: encoding and CRC of up to 45 bytes).
 */

static mc_t mc;
static monitor_t mon;

static void host_frame(monitor_t *m, uint8_t cmd, const uint8_t *p, uint8_t len)
{
    uint16_t crc = 0xFFFFU;
    uint8_t i;
    monitor_rx_byte(m, MONITOR_SOF);
    monitor_rx_byte(m, len);
    crc = monitor_crc16(crc, len);
    monitor_rx_byte(m, cmd);
    crc = monitor_crc16(crc, cmd);
    for (i = 0; i < len; i++) {
        monitor_rx_byte(m, p[i]);
        crc = monitor_crc16(crc, p[i]);
    }
    monitor_rx_byte(m, (uint8_t)(crc & 0xFFU));
    monitor_rx_byte(m, (uint8_t)(crc >> 8));
}

static void drain(void)
{
    uint8_t b;
    while (monitor_tx_byte(&mon, &b)) {
        bench_sink += b;
    }
}

static void setup_stream(uint16_t decim)
{
    const uint8_t sel[7] = {(uint8_t)(decim & 0xFFU), (uint8_t)(decim >> 8), 4, 2, 3, 7, 8};
    const uint8_t start[2] = {MONITOR_MODE_STREAM, MONITOR_TRIG_NOW};
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    monitor_init(&mon);
    host_frame(&mon, MONITOR_CMD_SELECT, sel, 7);
    host_frame(&mon, MONITOR_CMD_START, start, 2);
    drain();
}

static void run_stopped(uint32_t n)
{
    uint32_t k;
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    monitor_init(&mon);
    for (k = 0U; k < n; k++) {
        bench_sink += monitor_sample(&mon, &mc) ? 1 : 0;
    }
}

static void run_stream(uint32_t n, uint16_t decim)
{
    uint32_t k;
    setup_stream(decim);
    for (k = 0U; k < n; k++) {
        bench_sink += monitor_sample(&mon, &mc) ? 1 : 0;
        monitor_poll(&mon);
        drain();
    }
}

static void run_every_period(uint32_t n)
{
    run_stream(n, 1U);
}

static void run_decim10(uint32_t n)
{
    run_stream(n, 10U);
}

static void run_rx(uint32_t n)
{
    const uint8_t sel[7] = {10, 0, 4, 2, 3, 7, 8};
    uint32_t k = 0;
    mc_init(&mc);
    sim_mailbox_attach(&mc);
    monitor_init(&mon);
    /* 12 bytes per SELECT frame, each byte one measured call */
    while (k + 12U <= n) {
        host_frame(&mon, MONITOR_CMD_SELECT, sel, 7);
        drain();
        k += 12U;
    }
}

static void run_poll(uint32_t n)
{
    uint32_t k;
    uint8_t s;
    setup_stream(1U);
    for (k = 0U; k < n; k++) {
        for (s = 0; s < 4U; s++) {
            bench_sink += monitor_sample(&mon, &mc) ? 1 : 0;
        }
        monitor_poll(&mon);
        drain();
    }
}

void bench_monitor(void)
{
    bench_add("monitor_sample/stopped", "monitor_sample", 2000U, run_stopped);
    bench_add("monitor_sample/4ch_every_period", "monitor_sample", 2000U, run_every_period);
    bench_add("monitor_sample/4ch_decim10", "monitor_sample", 5000U, run_decim10);
    bench_add("monitor_rx_byte/select_frames", "monitor_rx_byte", 1200U, run_rx);
    bench_add("monitor_poll/4ch_data_frame", "monitor_poll", 1000U, run_poll);
}
