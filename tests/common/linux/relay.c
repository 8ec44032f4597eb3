/* The port tests' pty relay. See relay.h. */
#include "common/linux/relay.h"

#include <setjmp.h>
#include <stdarg.h>
#include <string.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>
#include <cmocka.h>

static void *relay_main(void *arg)
{
    struct relay *r = arg;
    for (;;) {
        struct pollfd pf[2];
        uint8_t buf[512];
        int i, stop;
        pthread_mutex_lock(&r->mu);
        stop = r->stop;
        pthread_mutex_unlock(&r->mu);
        if (stop) break;
        pf[0].fd = r->ma;
        pf[1].fd = r->mb;
        pf[0].events = pf[1].events = POLLIN;
        pf[0].revents = pf[1].revents = 0;
        if (poll(pf, 2, 10) <= 0) continue;
        for (i = 0; i < 2; i++) {
            ssize_t n;
            int to = i == 0 ? r->mb : r->ma, inject = 0;
            if (!(pf[i].revents & POLLIN)) continue;
            n = read(pf[i].fd, buf, sizeof buf);
            if (n <= 0) continue;
            pthread_mutex_lock(&r->mu);
            if (i == 0 && r->junk_to_sink > 0) { r->junk_to_sink--; inject = 1; }
            if (i == 1 && r->junk_to_sim > 0) { r->junk_to_sim--; inject = 1; }
            if (inject) r->injected++;
            pthread_mutex_unlock(&r->mu);
            /* a failed write loses the chunk, as a noisy line would: the test counts on the
             * sink's recovery, not on the relay */
            if (inject && write(to, r->junk, r->junk_len) != (ssize_t)r->junk_len) continue;
            if (write(to, buf, (size_t)n) != n) continue;
        }
    }
    return NULL;
}

void relay_open(struct relay *r, const uint8_t *junk, size_t junk_len)
{
    struct termios raw;
    memset(r, 0, sizeof *r);
    r->junk = junk;
    r->junk_len = junk_len;
    pthread_mutex_init(&r->mu, NULL);
    assert_int_equal(openpty(&r->ma, &r->sa, r->path_a, NULL, NULL), 0);
    assert_int_equal(openpty(&r->mb, &r->sb, r->path_b, NULL, NULL), 0);
    assert_int_equal(tcgetattr(r->ma, &raw), 0);
    cfmakeraw(&raw);
    assert_int_equal(tcsetattr(r->ma, TCSANOW, &raw), 0);
    assert_int_equal(tcsetattr(r->mb, TCSANOW, &raw), 0);
    assert_int_equal(pthread_create(&r->th, NULL, relay_main, r), 0);
}

void relay_junk(struct relay *r, int to_sink)
{
    pthread_mutex_lock(&r->mu);
    if (to_sink) r->junk_to_sink++;
    else r->junk_to_sim++;
    pthread_mutex_unlock(&r->mu);
}

void relay_close(struct relay *r)
{
    pthread_mutex_lock(&r->mu);
    r->stop = 1;
    pthread_mutex_unlock(&r->mu);
    pthread_join(r->th, NULL);
    close(r->ma);
    close(r->mb);
    close(r->sa);
    close(r->sb);
    pthread_mutex_destroy(&r->mu);
}
