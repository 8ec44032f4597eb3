/*
 * tools/fmath-fit-atan.c - how lib/src/fmath.c's atan polynomial was made (not built by make):
 *   gcc -O2 tools/fmath-fit-atan.c -lm -o build/fit-atan && build/fit-atan
 * Fits P(z) = (atan(u) - u)/u^3, z = u^2, on [0, tan^2(pi/8)] by interpolation at the
 * Chebyshev nodes (long double), rounds the coefficients to float and prints them with the
 * worst error of the rounded polynomial relative to atan(u) over a dense grid, for degrees 4..7.
 */
#include <math.h>
#include <stdio.h>

#define ZMAX 0.171572875253809902396622551580603843L /* tan^2(pi/8) = (sqrt 2 - 1)^2 */

static long double p_exact(long double z)
{
    long double u;
    if (z < 1e-12L) return -1.0L / 3 + z / 5;
    u = sqrtl(z);
    return (atanl(u) - u) / (z * u);
}

int main(void)
{
    int n, m, i, j, c, r, k, p;
    for (n = 4; n <= 7; n++) {
        long double a[8][9], worst = 0;
        float cf[8];
        m = n + 1;
        for (i = 0; i < m; i++) {
            long double t = cosl((2 * i + 1) * 3.14159265358979323846L / (2 * m));
            long double z = (t + 1) / 2 * ZMAX;
            for (j = 0; j < m; j++) a[i][j] = powl(z, j);
            a[i][m] = p_exact(z);
        }
        for (c = 0; c < m; c++) { /* Gauss-Jordan with partial pivoting */
            p = c;
            for (r = c + 1; r < m; r++) if (fabsl(a[r][c]) > fabsl(a[p][c])) p = r;
            for (k = 0; k <= m; k++) { long double t = a[c][k]; a[c][k] = a[p][k]; a[p][k] = t; }
            for (r = 0; r < m; r++) {
                if (r == c) continue;
                long double f = a[r][c] / a[c][c];
                for (k = c; k <= m; k++) a[r][k] -= f * a[c][k];
            }
        }
        for (j = 0; j < m; j++) cf[j] = (float)(a[j][m] / a[j][j]);
        for (i = 1; i <= 200000; i++) {
            long double z = ZMAX * i / 200000, u = sqrtl(z), v = 0, e;
            for (j = m - 1; j >= 0; j--) v = v * z + cf[j];
            e = fabsl((v - p_exact(z)) * z * u / atanl(u));
            if (e > worst) worst = e;
        }
        printf("degree %d: worst %.3Le relative (%.3Lf ulp)\n", n, worst, worst / ldexpl(1, -24));
        for (j = 0; j < m; j++) printf("  %a\n", (double)cf[j]);
    }
    return 0;
}
