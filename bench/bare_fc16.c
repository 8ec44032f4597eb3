/*
 * bench/bare_fc16.c - the baseline for `qorient stream` throughput: a bare libmodbus loop
 * writing N int32 joints (2N registers, one FC16) to a server for S seconds, as fast as the
 * server answers. Prints "bare_fc16: updates U seconds S updates_per_s R".
 *
 *   build/bench/bare_fc16 HOST PORT [JOINTS=6] [SECONDS=3]
 *
 * Used by tools/bench-stream.sh against the same `qorient sim` as the stream, in the same run.
 */
#include <errno.h>
#include <modbus.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

int main(int argc, char **argv)
{
    modbus_t *ctx;
    uint16_t regs[246];
    int joints = argc > 3 ? atoi(argv[3]) : 6;
    double seconds = argc > 4 ? atof(argv[4]) : 3.0, t0, t;
    long updates = 0, errors = 0;
    if (argc < 3 || joints < 1 || joints > 61 || !(seconds > 0)) {
        fprintf(stderr, "usage: bare_fc16 HOST PORT [JOINTS] [SECONDS]\n");
        return 2;
    }
    ctx = modbus_new_tcp(argv[1], atoi(argv[2]));
    if (ctx == NULL || modbus_connect(ctx) != 0) {
        fprintf(stderr, "bare_fc16: cannot connect to %s:%s: %s\n", argv[1], argv[2], modbus_strerror(errno));
        return 1;
    }
    modbus_set_slave(ctx, 1);
    modbus_set_response_timeout(ctx, 0, 50000);
    memset(regs, 0, sizeof regs);
    t0 = now_s();
    do {
        /* the same values a stream would send: a slowly moving int32 per joint, high word first */
        int j;
        for (j = 0; j < joints; j++) {
            int32_t v = (int32_t)(updates % 1000) + j;
            regs[2 * j] = (uint16_t)((uint32_t)v >> 16);
            regs[2 * j + 1] = (uint16_t)((uint32_t)v & 0xffffu);
        }
        if (modbus_write_registers(ctx, 0, 2 * joints, regs) == 2 * joints) updates++;
        else { errors++; modbus_flush(ctx); }
        t = now_s();
    } while (t - t0 < seconds);
    printf("bare_fc16: updates %ld errors %ld seconds %.3f updates_per_s %.0f\n", updates, errors, t - t0,
           updates / (t - t0));
    modbus_close(ctx);
    modbus_free(ctx);
    return 0;
}
