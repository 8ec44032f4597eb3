/*
 * fuzz/fuzz_cli_common.h - running a `qorient` subcommand entry point (cli/cli.h)
 * inside a fuzz target: the fuzzer's bytes become the command's input (a temporary file, given
 * as FILE or put on fd 0 under stdin), its standard output is captured in a second temporary
 * file and checked, its standard error goes to /dev/null (set QO_FUZZ_VERBOSE=1 to keep it).
 *
 * Index:
 *   qo_fz_cli_run          run fn(argc, argv) with the input on stdin or as a file; returns
 *                          the exit status, *out the captured output (NUL-terminated)
 *   qo_fz_cli_check_output every output line is "error: ...", a copied blank/'#' line, or a
 *                          list of finite numbers (the "every output finite or an error" rule)
 *   qo_fz_cli_prescan      the numbers of the input, for the targets that bound the volume of
 *                          output they ask for (a rate-sampled command writes span * rate rows
 *                          by design; a fuzzer would only find that this takes long)
 */
#ifndef QORIENT_FUZZ_CLI_COMMON_H
#define QORIENT_FUZZ_CLI_COMMON_H

#include <getopt.h>
#include <fcntl.h>
#include <unistd.h>

#include "fuzz_common.h"
#include "../cli/cli.h"

typedef int (*qo_fz_cli_fn)(int argc, char **argv);

/* QO_FUZZ_CLI_EXEC (tests/fuzz/test_fuzz_regress.c, which is not linked with the command's
 * objects): run the built command $QORIENT (default build/qorient) as a child process with the
 * same argv instead of calling the entry point in process. */
#ifdef QO_FUZZ_CLI_EXEC
#include <sys/wait.h>
#define QO_FZ_CLI_FN(fn) ((qo_fz_cli_fn)NULL)
#else
#define QO_FZ_CLI_FN(fn) (fn)
#endif

/* Temporary files, created once per process and rewritten per input. */
typedef struct qo_fz_cli_files {
    int in_fd, out_fd, null_fd;
    char in_path[64], out_path[64];
} qo_fz_cli_files;

static inline qo_fz_cli_files *qo_fz_cli_files_get(void)
{
    static qo_fz_cli_files f;
    static int ready;
    if (!ready) {
        strcpy(f.in_path, "/tmp/qo-fuzz-in-XXXXXX");
        strcpy(f.out_path, "/tmp/qo-fuzz-out-XXXXXX");
        f.in_fd = mkstemp(f.in_path);
        f.out_fd = mkstemp(f.out_path);
        f.null_fd = open("/dev/null", O_WRONLY);
        if (f.in_fd < 0 || f.out_fd < 0 || f.null_fd < 0) {
            perror("fuzz: temporary files");
            abort();
        }
        /* Unlinked at once (nothing is left in /tmp); the command opens the input through
         * /proc/self/fd, which stays valid while the descriptor is open. */
        unlink(f.in_path);
        unlink(f.out_path);
        snprintf(f.in_path, sizeof f.in_path, "/proc/self/fd/%d", f.in_fd);
        ready = 1;
    }
    return &f;
}

static inline void qo_fz_cli_write_all(int fd, const uint8_t *p, size_t n)
{
    if (ftruncate(fd, 0) != 0 || lseek(fd, 0, SEEK_SET) != 0) abort();
    while (n > 0) {
        ssize_t w = write(fd, p, n);
        if (w <= 0) abort();
        p += w;
        n -= (size_t)w;
    }
    if (lseek(fd, 0, SEEK_SET) != 0) abort();
}

/* Runs fn with argv (argv[argc] must be NULL). use_stdin: the input is put on fd 0 and stdin
 * rewound; otherwise the caller passes qo_fz_cli_files_get()->in_path as FILE in argv.
 * *out is malloc'd (free it), NUL-terminated, *out_len its length. */
static inline int qo_fz_cli_run(qo_fz_cli_fn fn, int argc, char **argv, int use_stdin, const uint8_t *in,
                                size_t n, char **out, size_t *out_len)
{
    qo_fz_cli_files *f = qo_fz_cli_files_get();
    int save0 = -1, save1, save2, rc, quiet = getenv("QO_FUZZ_VERBOSE") == NULL;
    off_t len;
    char *buf;

    qo_fz_cli_write_all(f->in_fd, in, n);
    if (ftruncate(f->out_fd, 0) != 0 || lseek(f->out_fd, 0, SEEK_SET) != 0) abort();
    fflush(stdout);
    fflush(stderr);
    if (use_stdin) {
        save0 = dup(0);
        if (save0 < 0 || dup2(f->in_fd, 0) < 0) abort();
        clearerr(stdin);
        if (fseek(stdin, 0L, SEEK_SET) != 0) abort();   /* drops any buffered input */
    }
    save1 = dup(1);
    save2 = dup(2);
    if (save1 < 0 || save2 < 0 || dup2(f->out_fd, 1) < 0 || (quiet && dup2(f->null_fd, 2) < 0)) abort();

#ifdef QO_FUZZ_CLI_EXEC
    {
        const char *exe = getenv("QORIENT") != NULL ? getenv("QORIENT") : "build/qorient";
        char *av[40];
        int k, ws;
        pid_t pid;
        (void)fn;
        av[0] = (char *)"qorient";
        for (k = 0; k < argc && k < 38; k++) av[k + 1] = argv[k];
        av[k + 1] = NULL;
        fflush(NULL);
        pid = fork();
        if (pid < 0) abort();
        if (pid == 0) {
            execv(exe, av);
            _exit(127);
        }
        if (waitpid(pid, &ws, 0) != pid) abort();
        rc = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
    }
#else
    optind = 0;   /* glibc: full re-initialisation of getopt_long */
    rc = fn(argc, argv);
#endif

    fflush(stdout);
    fflush(stderr);
    if (dup2(save1, 1) < 0 || dup2(save2, 2) < 0) abort();
    close(save1);
    close(save2);
    if (use_stdin) {
        if (dup2(save0, 0) < 0) abort();
        close(save0);
        clearerr(stdin);
    }
    len = lseek(f->out_fd, 0, SEEK_END);
    if (len < 0 || lseek(f->out_fd, 0, SEEK_SET) != 0) abort();
    buf = malloc((size_t)len + 1);
    if (buf == NULL) abort();
    if (len > 0 && read(f->out_fd, buf, (size_t)len) != (ssize_t)len) abort();
    buf[len] = '\0';
    *out = buf;
    *out_len = (size_t)len;
    return rc;
}

/* Every line: "error: REASON", empty or '#' (copied from the input), or numbers separated by
 * commas/blanks, each finite. Returns 1 when the output satisfies that, else names the line. */
static inline void qo_fz_cli_check_output(const char *out, const char *what)
{
    const char *line = out;
    unsigned long lineno = 0;
    while (*line != '\0') {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        char tmp[512];
        const char *p = line;
        lineno++;
        while (p < line + len && (*p == ' ' || *p == '\t')) p++;
        if (p == line + len || *p == '#' || strncmp(line, "error: ", 7) == 0) {
            /* copied input line or an error record */
        } else {
            char *q, *e;
            QO_FUZZ_CHECK(len < sizeof tmp, "%s: output line %lu is %zu characters long", what, lineno, len);
            memcpy(tmp, line, len);
            tmp[len] = '\0';
            q = tmp;
            for (;;) {
                double v;
                while (*q == ' ' || *q == '\t' || *q == ',') q++;
                if (*q == '\0') break;
                v = strtod(q, &e);
                QO_FUZZ_CHECK(e != q, "%s: output line %lu is neither numbers nor an error: '%s'", what, lineno, tmp);
                QO_FUZZ_CHECK(isfinite(v), "%s: output line %lu has a non-finite number: '%s'", what, lineno, tmp);
                q = e;
            }
        }
        if (end == NULL) break;
        line = end + 1;
    }
}

/* Scans the input as the commands do (lines, qo_cli_parse_numbers). Returns the largest
 * |number| on any line (0 for none; NaN/Inf count as HUGE_VAL), and the first and last
 * finite value of column 0 in *t_lo / *t_hi (min and max). */
static inline double qo_fz_cli_prescan(const uint8_t *in, size_t n, double *t_lo, double *t_hi)
{
    char *text = malloc(n + 1), *line;
    double big = 0.0, v[64];
    *t_lo = HUGE_VAL;
    *t_hi = -HUGE_VAL;
    if (text == NULL) abort();
    memcpy(text, in, n);
    text[n] = '\0';
    line = text;
    while (line != NULL) {
        char *nl = strchr(line, '\n');
        size_t k, m;
        size_t ll;
        if (nl) *nl = '\0';
        /* as qo_cli_getline: trailing CR/LF removed */
        ll = strlen(line);
        while (ll > 0 && (line[ll - 1] == '\r' || line[ll - 1] == '\n')) line[--ll] = '\0';
        if (qo_cli_parse_numbers(line, v, 64, &m) == -2) {
            m = 64;
            big = HUGE_VAL;   /* more columns than scanned: magnitude unknown */
        }
        for (k = 0; k < m; k++) {
            double a = isfinite(v[k]) ? fabs(v[k]) : HUGE_VAL;
            if (a > big) big = a;
        }
        if (m > 0 && isfinite(v[0])) {
            if (v[0] < *t_lo) *t_lo = v[0];
            if (v[0] > *t_hi) *t_hi = v[0];
        }
        line = nl ? nl + 1 : NULL;
    }
    free(text);
    return big;
}

#endif /* QORIENT_FUZZ_CLI_COMMON_H */
