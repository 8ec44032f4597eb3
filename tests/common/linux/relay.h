/*
 * tests/common/linux/relay.h - the port tests' RTU line: two pseudo-terminal pairs joined by
 * a relay thread that copies bytes both ways and can put a garbage chunk in front of the next
 * chunk in either direction. The simulator opens path_a, the sink path_b. Linux only (pty,
 * pthread), hence its own folder: the .c files of tests/common itself also build for Cortex-M.
 *
 *   relay_open(&r, junk, n)   opens both pairs (raw mode) and starts the thread; cmocka
 *                             assertions on failure. junk (n bytes, kept by pointer) is what
 *                             an injection writes.
 *   relay_junk(&r, to_sink)   one more injection before the next chunk towards the sink
 *                             (a garbled reply) or, to_sink 0, towards the simulator (a
 *                             garbled request); r.injected counts those done.
 *   relay_close(&r)           stops the thread, closes every descriptor.
 */
#ifndef QORIENT_TESTS_LINUX_RELAY_H
#define QORIENT_TESTS_LINUX_RELAY_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>

struct relay {
    int ma, mb;          /* masters: A = simulator side, B = sink side */
    int sa, sb;          /* slaves kept open so the masters never read EIO */
    char path_a[64], path_b[64];
    pthread_t th;
    pthread_mutex_t mu;
    int stop;
    int junk_to_sink, junk_to_sim; /* chunks still to prefix with garbage */
    const uint8_t *junk;
    size_t junk_len;
    uint64_t injected;
};

void relay_open(struct relay *r, const uint8_t *junk, size_t junk_len);
void relay_junk(struct relay *r, int to_sink);
void relay_close(struct relay *r);

#endif
