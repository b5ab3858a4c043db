/* sim_pty.c - the live data monitor on a pseudo-terminal (see sim_pty.h). */
/* posix_openpt, grantpt, unlockpt, ptsname, nanosleep, clock_gettime, sigaction: POSIX/XSI, not
 * C99. */
#define _XOPEN_SOURCE 600
#include "sim_pty.h"

#include "sim_parse.h"

#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "monitor.h"
#include "sim_mailbox.h"

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

void sim_pty_cfg_default(sim_pty_cfg_t *cfg)
{
    cfg->speed = 1.0;
    cfg->baud = 38400L; /* HAL_UART_BAUD of the dsPIC build */
    cfg->duration_s = 0.0;
    cfg->truth_path = NULL;
}

static double wall_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void sleep_s(double s)
{
    struct timespec ts;
    if (s <= 0.0) {
        return;
    }
    ts.tv_sec = (time_t)s;
    ts.tv_nsec = (long)((s - (double)ts.tv_sec) * 1e9);
    nanosleep(&ts, NULL);
}

/* Raw 8-bit line on the slave side: no echo, no CR/LF translation, no signals. */
static void make_raw(int fd)
{
    struct termios t;
    if (tcgetattr(fd, &t) != 0) {
        return;
    }
    t.c_iflag &= ~(tcflag_t)(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON);
    t.c_oflag &= ~(tcflag_t)OPOST;
    t.c_lflag &= ~(tcflag_t)(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    t.c_cflag &= ~(tcflag_t)(CSIZE | PARENB);
    t.c_cflag |= (tcflag_t)CS8;
    t.c_cc[VMIN] = 1;
    t.c_cc[VTIME] = 0;
    tcsetattr(fd, TCSANOW, &t);
}

int sim_pty_run(simcore_t *s, const sim_pty_cfg_t *cfg)
{
    static monitor_t mon;
    const long periods_per_ms = PWM_FREQUENCY_HZ / 1000L;
    const double bytes_per_ms = (double)cfg->baud / 10.0 / 1000.0;
    /* what the line may bank: 64 bytes, or two milliseconds' worth at a
     * rate that sends more than 32 a millisecond (up to --baud's 1 MBd) */
    const double tx_cap = (2.0 * bytes_per_ms > 64.0) ? 2.0 * bytes_per_ms : 64.0;
    double tx_credit = 0.0, t0_wall, ms = 0.0;
    int master, slave;
    const char *name;
    FILE *truth = NULL;
    long rec_no = -1, k;
    int pending = -1; /* a byte taken from the monitor that the pty did not take yet */
    struct sigaction sa;

    if (cfg->truth_path != NULL) {
        truth = fopen(cfg->truth_path, "w");
        if (truth == NULL) {
            char pq[256], why[300]; /* the path, quoted: one line whatever it holds */
            sim_parse_msg(why, sizeof(why), "cannot write '%s'",
                          sim_parse_quote(cfg->truth_path, pq, sizeof(pq)));
            return sim_refuse("sim", "--truth", why);
        }
        fprintf(truth, "rec,index,t_s,speed_true_rpm,speed_est_rpm,state\n");
    }

    master = posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0 ||
        (name = ptsname(master)) == NULL) {
        fprintf(stderr, "sim: cannot open a pseudo-terminal: %s\n", strerror(errno));
        return 2;
    }
    /* Keep one slave descriptor open (never read): the master then never
     * sees EIO between two clients, and the line stays raw. */
    slave = open(name, O_RDWR | O_NOCTTY);
    if (slave < 0) {
        fprintf(stderr, "sim: cannot open %s: %s\n", name, strerror(errno));
        return 2;
    }
    make_raw(slave);
    fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);

    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    sim_mailbox_attach(&s->mc); /* the monitor's commands act on this motor */
    monitor_init(&mon);
    printf("pty: %s\n", name);
    printf("   monitor: UART %ld Bd emulated, %.3g x real time%s, PWM %ld Hz\n", cfg->baud,
           cfg->speed, cfg->speed <= 0.0 ? " (free-running)" : "", (long)PWM_FREQUENCY_HZ);
    fflush(stdout);

    t0_wall = wall_s();
    while (stop_requested == 0 && !s->diverged &&
           (cfg->duration_s <= 0.0 || s->rig.t < cfg->duration_s)) {
        uint8_t in[64];

        /* the ISR, once per PWM period */
        for (k = 0; k < periods_per_ms; k++) {
            simcore_step(s);
            if (monitor_sample(&mon, &s->mc)) {
                uint16_t idx = (uint16_t)(mon.wr - 1U);
                if (idx == 0U) {
                    rec_no++;
                }
                if (truth != NULL) {
                    fprintf(truth, "%ld,%u,%.6f,%.4f,%.4f,%d\n", rec_no, (unsigned)idx, s->now.t_s,
                            s->now.speed_rpm, s->now.speed_est_rpm, s->now.state);
                }
            }
        }
        ms += 1.0;

        /* the main loop, once per millisecond */
        while (monitor_rx_ready(&mon)) {
            if (read(master, in, 1) != 1) {
                break;
            }
            monitor_rx_byte(&mon, in[0]);
        }
        monitor_tick_1ms(&mon);
        monitor_poll(&mon);
        tx_credit += bytes_per_ms;
        if (tx_credit > tx_cap) {
            tx_credit = tx_cap; /* an idle line does not bank a burst */
        }
        while (tx_credit >= 1.0) {
            uint8_t b;
            if (pending < 0) {
                if (!monitor_tx_byte(&mon, &b)) {
                    break;
                }
                pending = b;
            }
            in[0] = (uint8_t)pending;
            if (write(master, in, 1) != 1) {
                break; /* nobody reading: the byte waits */
            }
            pending = -1;
            tx_credit -= 1.0;
        }

        if (cfg->speed > 0.0) {
            double ahead = ms * 1e-3 / cfg->speed - (wall_s() - t0_wall);
            if (ahead > 0.002) {
                sleep_s(ahead);
            }
        }
    }
    if (truth != NULL) {
        fclose(truth);
    }
    close(slave);
    close(master);
    printf("   monitor: stopped at %.3f s simulated, %u error replies, %u frames dropped\n",
           s->rig.t, (unsigned)mon.rx_errors, (unsigned)mon.rx_dropped);
    if (s->diverged) {
        char why[320];
        simcore_diverged_msg(s, why, sizeof(why));
        fflush(stdout);
        fprintf(stderr, "sim: pty: %s\n", why);
        return 1;
    }
    return 0;
}
