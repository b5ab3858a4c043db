/* SPDX-License-Identifier: Apache-2.0 */
/* Copyright 2026 The open AN1078 authors */
/* sim_pty.c - the X2Cscope target on a pseudo-terminal and, optionally, TCP (see sim_pty.h). */
/* posix_openpt, grantpt, unlockpt, ptsname, nanosleep, clock_gettime, sigaction, sockets:
 * POSIX/XSI, not C99. */
#define _XOPEN_SOURCE 600
#include "sim_pty.h"

#include "sim_parse.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/inotify.h>
#include <sys/socket.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include "sim_mailbox.h"
#include "x2c.h"

static volatile sig_atomic_t stop_requested;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

void sim_pty_cfg_default(sim_pty_cfg_t *cfg)
{
    cfg->speed = 1.0;
    cfg->baud = 115200L; /* HAL_UART_BAUD of the dsPIC build, X2Cscope's default */
    cfg->tcp_port = 0;
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

/* A TCP listener on 127.0.0.1:port, non-blocking; -1 when it cannot be opened. */
static int tcp_listen(int port)
{
    struct sockaddr_in a;
    int one = 1;
    int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) {
        return -1;
    }
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(fd, (struct sockaddr *)&a, sizeof a) != 0 || listen(fd, 1) != 0) {
        close(fd);
        return -1;
    }
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    return fd;
}

int sim_pty_run(simcore_t *s, const sim_pty_cfg_t *cfg)
{
    static x2c_t x2c;
    const long periods_per_ms = PWM_FREQUENCY_HZ / 1000L;
    const double bytes_per_ms = (double)cfg->baud / 10.0 / 1000.0;
    /* what the line may bank: 64 bytes, or two milliseconds' worth at a
     * rate that sends more than 32 a millisecond (up to --baud's 1 MBd) */
    const double tx_cap = (2.0 * bytes_per_ms > 64.0) ? 2.0 * bytes_per_ms : 64.0;
    double tx_credit = 0.0, t0_wall, ms = 0.0;
    int master, slave, listener = -1, peer = -1;
    int out_fd; /* where replies go: the transport the last request came on */
    const char *name;
    FILE *truth = NULL;
    long rec_no = -1, k;
#if X2C_SCOPE
    uint8_t scope_was = X2C_SCOPE_IDLE;
#endif
    int pending = -1;         /* a byte taken from the target that the transport did not take yet */
    bool pty_replied = false; /* reply bytes went to the pty since its last request byte */
    int closes = -1;          /* inotify: a client closing the pty's line */
    bool pty_rx_new = false;  /* request bytes came on the pty since closes was last read */
    struct sigaction sa;

    if (cfg->truth_path != NULL) {
        truth = fopen(cfg->truth_path, "w");
        if (truth == NULL) {
            char pq[256], why[300]; /* the path, quoted: one line whatever it holds */
            sim_parse_msg(why, sizeof(why), "cannot write '%s'",
                          sim_parse_quote(cfg->truth_path, pq, sizeof(pq)));
            return sim_refuse("sim", "--truth", why);
        }
        fprintf(truth, "rec,at,t_s,speed_true_rpm,speed_est_rpm,state\n");
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
    /* A client that closes the line leaves unread whatever of a reply it had
     * not read; the next one to open it would read that as its answer. The
     * line's closes are watched (inotify sees every close of the device), and
     * each one discards the rest of the reply, on the line and in the target. */
    closes = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (closes >= 0 && inotify_add_watch(closes, name, IN_CLOSE_WRITE | IN_CLOSE_NOWRITE) < 0) {
        close(closes);
        closes = -1;
    }
    fcntl(master, F_SETFL, fcntl(master, F_GETFL) | O_NONBLOCK);
    out_fd = master;
    if (cfg->tcp_port > 0) {
        listener = tcp_listen(cfg->tcp_port);
        if (listener < 0) {
            fprintf(stderr, "sim: cannot listen on 127.0.0.1:%d: %s\n", cfg->tcp_port,
                    strerror(errno));
            return 2;
        }
    }

    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN); /* a TCP client that leaves mid-reply */

    sim_mailbox_attach(&s->mc); /* the target's writes act on this motor */
    x2c_init(&x2c);
    printf("pty: %s\n", name);
    if (listener >= 0) {
        printf("tcp: 127.0.0.1:%d\n", cfg->tcp_port);
    }
    printf("   x2cscope: UART %ld Bd emulated, %.3g x real time%s, PWM %ld Hz\n", cfg->baud,
           cfg->speed, cfg->speed <= 0.0 ? " (free-running)" : "", (long)PWM_FREQUENCY_HZ);
    fflush(stdout);

    t0_wall = wall_s();
    while (stop_requested == 0 && !s->diverged &&
           (cfg->duration_s <= 0.0 || s->rig.t < cfg->duration_s)) {
        uint8_t in[64];

        /* the ISR, once per PWM period */
        for (k = 0; k < periods_per_ms; k++) {
            uint16_t at;
            simcore_step(s);
#if X2C_SCOPE
            if (x2c.scope.run.state != X2C_SCOPE_IDLE && scope_was == X2C_SCOPE_IDLE) {
                rec_no++; /* a capture started */
            }
#endif
            if (x2c_sample(&x2c, &at) && truth != NULL) {
                fprintf(truth, "%ld,%u,%.6f,%.4f,%.4f,%d\n", rec_no, (unsigned)at, s->now.t_s,
                        s->now.speed_rpm, s->now.speed_est_rpm, s->now.state);
            }
#if X2C_SCOPE
            scope_was = x2c.scope.run.state;
#endif
        }
        ms += 1.0;

        /* the main loop, once per millisecond: a TCP client may connect */
        if (listener >= 0 && peer < 0) {
            peer = accept(listener, NULL, NULL);
            if (peer >= 0) {
                int one = 1;
                fcntl(peer, F_SETFL, fcntl(peer, F_GETFL) | O_NONBLOCK);
                setsockopt(peer, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
            }
        }
        if (closes >= 0) {
            char ev[sizeof(struct inotify_event) + 256];
            /* a close seen together with request bytes is the last client's,
             * which left before this one asked: the request's own flush took
             * the line, and this reply is the new client's */
            if (read(closes, ev, sizeof ev) > 0 && out_fd == master && !pty_rx_new) {
                uint8_t b;
                tcflush(slave, TCIFLUSH);
                while (x2c_tx_byte(&x2c, &b)) {
                }
                pending = -1;
                pty_replied = false;
            }
            pty_rx_new = false;
        }
        while (x2c_rx_ready(&x2c)) {
            if (read(master, in, 1) == 1) {
                if (pty_replied) {
                    /* A request's first byte: the client has read its last reply, or
                     * gave it up, or it left and this is another one. Whatever of that
                     * reply is still on the line is nobody's answer now: the new
                     * client must not read it as its own (a client that ignores error
                     * codes, as pyx2cscope does, would read every later reply one
                     * behind). The flush takes the kernel's buffers too. */
                    tcflush(slave, TCIFLUSH);
                    pty_replied = false;
                }
                pty_rx_new = true;
                out_fd = master;
            } else if (peer >= 0) {
                ssize_t r = read(peer, in, 1);
                if (r == 0 || (r < 0 && errno != EAGAIN && errno != EWOULDBLOCK)) {
                    close(peer); /* the client left */
                    peer = -1;
                    out_fd = master;
                    break;
                }
                if (r != 1) {
                    break;
                }
                out_fd = peer;
            } else {
                break;
            }
            x2c_rx_byte(&x2c, in[0]);
        }
        x2c_tick_1ms(&x2c); /* the board's inter-byte timeout, at the simulated ms */
        tx_credit += bytes_per_ms;
        if (tx_credit > tx_cap) {
            tx_credit = tx_cap; /* an idle line does not bank a burst */
        }
        while (tx_credit >= 1.0) {
            uint8_t b;
            if (pending < 0) {
                if (!x2c_tx_byte(&x2c, &b)) {
                    break;
                }
                pending = b;
            }
            in[0] = (uint8_t)pending;
            if (write(out_fd, in, 1) != 1) {
                if (out_fd == peer && errno != EAGAIN && errno != EWOULDBLOCK) {
                    /* the TCP client left mid-reply: the rest of it is nobody's; the target
                     * takes requests again (the pty's and the next client's) */
                    close(peer);
                    peer = -1;
                    out_fd = master;
                    while (x2c_tx_byte(&x2c, &b)) {
                    }
                    pending = -1;
                }
                break; /* else nobody reading: the byte waits */
            }
            pending = -1;
            tx_credit -= 1.0;
            pty_replied = pty_replied || out_fd == master;
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
    if (peer >= 0) {
        close(peer);
    }
    if (listener >= 0) {
        close(listener);
    }
    if (closes >= 0) {
        close(closes);
    }
    close(slave);
    close(master);
    printf("   x2cscope: stopped at %.3f s simulated, %u replies, %u refusals\n", s->rig.t,
           (unsigned)x2c.answered, (unsigned)x2c.refused);
    if (s->diverged) {
        char why[320];
        simcore_diverged_msg(s, why, sizeof(why));
        fflush(stdout);
        fprintf(stderr, "sim: pty: %s\n", why);
        return 1;
    }
    return 0;
}
