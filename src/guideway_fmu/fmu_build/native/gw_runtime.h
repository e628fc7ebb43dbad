/* Run-time support of the C that fmu_build/native translates from the Python physics:
 * the failure message (formatted as Python formats it) and the few operations whose Python
 * meaning differs from C's operator (modulo, floor division, sign, max/min with NaN). */
#ifndef GW_RUNTIME_H
#define GW_RUNTIME_H

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GW_MESSAGE_SIZE 1024
#define GW_PI 3.14159265358979323846

typedef struct {
    char message[GW_MESSAGE_SIZE]; /* why the last translated call failed */
    size_t length;
    double *scratch; /* the run-time arrays of the translated functions (gw_scratch) */
    size_t scratch_size;
} gw_ctx;

/* ``n`` doubles on the heap for a translated function's run-time arrays, kept by the context
 * (one per instance) and grown to the largest need: a function of many arrays would otherwise
 * need more stack than a host's thread may have (1 MB on Windows). NULL when out of memory. */
static double *gw_scratch(gw_ctx *ctx, size_t n) {
    if (n > ctx->scratch_size) {
        double *grown = (double *)realloc(ctx->scratch, n * sizeof(double));
        if (!grown) return NULL;
        ctx->scratch = grown;
        ctx->scratch_size = n;
    }
    return ctx->scratch;
}

static void gw_msg_clear(gw_ctx *ctx) { ctx->length = 0; ctx->message[0] = '\0'; }

static void gw_msg_text(gw_ctx *ctx, const char *text) {
    size_t room = GW_MESSAGE_SIZE - 1 - ctx->length, n = strlen(text);
    if (n > room) n = room;
    memcpy(ctx->message + ctx->length, text, n);
    ctx->length += n;
    ctx->message[ctx->length] = '\0';
}

/* Words of a text as Python's str.split() splits ASCII text: runs of whitespace separate. */
static long gw_words(const char *text) {
    long n = 0;
    while (*text) {
        while (*text && strchr(" \t\n\r\v\f", *text)) ++text;
        if (!*text) break;
        ++n;
        while (*text && !strchr(" \t\n\r\v\f", *text)) ++text;
    }
    return n;
}

/* Word k of ``text`` (str.split()) copied into ``out`` (cut to ``size`` - 1 bytes). */
static void gw_word(const char *text, long k, char *out, size_t size) {
    size_t n = 0;
    for (;;) {
        while (*text && strchr(" \t\n\r\v\f", *text)) ++text;
        if (!*text) break;
        if (k-- == 0) {
            while (*text && !strchr(" \t\n\r\v\f", *text) && n + 1 < size) out[n++] = *text++;
            break;
        }
        while (*text && !strchr(" \t\n\r\v\f", *text)) ++text;
    }
    out[n] = '\0';
}

/* float(word) of word k: 0, or 1 when Python's float() refuses it (the value then NaN). C's
 * strtod reads hexadecimal numbers too, which float() refuses; digit underscores, which
 * float() accepts, are refused here, and so is a word too long for the buffer (never cut). */
static int gw_word_double(const char *text, long k, double *value) {
    char word[512], *end;
    gw_word(text, k, word, sizeof word);
    *value = strtod(word, &end);
    if (end == word || *end || strchr(word, 'x') || strchr(word, 'X')
        || strlen(word) == sizeof word - 1) {
        *value = NAN;
        return 1;
    }
    return 0;
}

static void gw_msg_long(gw_ctx *ctx, long value) {
    char text[32];
    snprintf(text, sizeof text, "%ld", value);
    gw_msg_text(ctx, text);
}

/* Python's repr of a float: the shortest digits that read back to the same double, fixed
 * notation for decimal exponents -4 to 15, scientific (two exponent digits at least) else. */
static void gw_repr(char *out, size_t size, double x) {
    char digits[32], text[40];
    int precision, exponent, n, i;
    if (isnan(x)) { snprintf(out, size, "nan"); return; }
    if (isinf(x)) { snprintf(out, size, x > 0 ? "inf" : "-inf"); return; }
    for (precision = 1; precision <= 17; ++precision) {
        snprintf(text, sizeof text, "%.*e", precision - 1, x);
        if (strtod(text, NULL) == x) break;
    }
    {   /* text is [-]d[.ddd]e[+-]xx: collect the digits and the exponent */
        const char *p = text;
        int negative = (*p == '-');
        char *end;
        if (negative) ++p;
        n = 0;
        for (; *p && *p != 'e'; ++p) if (*p != '.') digits[n++] = *p;
        while (n > 1 && digits[n - 1] == '0') --n;
        digits[n] = '\0';
        exponent = (int)strtol(p + 1, &end, 10);
        {
            char body[64];
            size_t k = 0;
            if (exponent >= -4 && exponent < 16) {
                if (exponent >= n - 1) {
                    for (i = 0; i < n; ++i) body[k++] = digits[i];
                    for (i = n - 1; i < exponent; ++i) body[k++] = '0';
                    body[k++] = '.'; body[k++] = '0';
                } else if (exponent >= 0) {
                    for (i = 0; i <= exponent; ++i) body[k++] = digits[i];
                    body[k++] = '.';
                    for (; i < n; ++i) body[k++] = digits[i];
                } else {
                    body[k++] = '0'; body[k++] = '.';
                    for (i = -1; i > exponent; --i) body[k++] = '0';
                    for (i = 0; i < n; ++i) body[k++] = digits[i];
                }
                body[k] = '\0';
            } else {
                body[k++] = digits[0];
                if (n > 1) { body[k++] = '.'; for (i = 1; i < n; ++i) body[k++] = digits[i]; }
                body[k] = '\0';
                snprintf(body + k, sizeof body - k, "e%c%02d", exponent < 0 ? '-' : '+',
                         exponent < 0 ? -exponent : exponent);
            }
            snprintf(out, size, "%s%s", negative ? "-" : "", body);
        }
    }
}

static void gw_msg_repr(gw_ctx *ctx, double x) {
    char text[40];
    gw_repr(text, sizeof text, x);
    gw_msg_text(ctx, text);
}

static void gw_msg_format(gw_ctx *ctx, const char *format, double x) {
    char text[64];
    snprintf(text, sizeof text, format, x);
    gw_msg_text(ctx, text);
}

static double gw_mod(double a, double b) { /* Python's a % b and np.mod: the sign of b */
    double r = fmod(a, b);  /* b = 0: NaN, numpy's answer (Python raises) */
    if (r != 0.0) { if ((r < 0.0) != (b < 0.0)) r += b; }
    else if (b == b && b != 0.0) r = copysign(0.0, b);
    return r;
}
static long gw_lmod(long a, long b) { long r = a % b; return (r != 0 && ((r < 0) != (b < 0))) ? r + b : r; }
static long gw_ldiv(long a, long b) { return (a - gw_lmod(a, b)) / b; }
static double gw_sign(double x) { return x > 0.0 ? 1.0 : x < 0.0 ? -1.0 : x; } /* np.sign: NaN, +-0 kept */
static double gw_npmax(double a, double b) { return isnan(a) ? a : isnan(b) ? b : a >= b ? a : b; }
static double gw_npmin(double a, double b) { return isnan(a) ? a : isnan(b) ? b : a <= b ? a : b; }
static double gw_pymax(double a, double b) { return b > a ? b : a; }
static double gw_pymin(double a, double b) { return b < a ? b : a; }
static long gw_pymaxl(long a, long b) { return b > a ? b : a; }
static long gw_pyminl(long a, long b) { return b < a ? b : a; }
static double gw_degrees(double x) { return x * (180.0 / 3.14159265358979323846); }
static double gw_radians(double x) { return x * (3.14159265358979323846 / 180.0); }

/* numpy's pairwise summation of n doubles (np.sum of a 1-D float array): below 8 a plain
 * loop, up to 128 eight partial sums, above that the halves summed apart. */
static double gw_pairwise(const double *a, long n) {
    if (n < 8) {
        double r = -0.0;
        long i;
        for (i = 0; i < n; ++i) r += a[i];
        return r;
    }
    if (n <= 128) {
        double r[8], res;
        long i, j;
        for (j = 0; j < 8; ++j) r[j] = a[j];
        for (i = 8; i < n - (n % 8); i += 8)
            for (j = 0; j < 8; ++j) r[j] += a[i + j];
        res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
        for (; i < n; ++i) res += a[i];
        return res;
    }
    {
        long half = n / 2;
        half -= half % 8;
        return gw_pairwise(a, half) + gw_pairwise(a + half, n - half);
    }
}

static double gw_np_sum(const double *a, long n) { return 0.0 + gw_pairwise(a, n); }

/* numpy.interp(x, xp, fp) of increasing nodes xp[0..n-1] (n >= 1): the end values held outside,
 * NaN at a NaN x, the same arithmetic as numpy's (slope from the left node, then the right one
 * where that gives NaN). */
static double gw_interp(double x, long n, const double *xp, const double *fp) {
    long lo = 0, hi = n - 1, mid;
    double slope, r;
    if (isnan(x)) return x;
    if (x < xp[0]) return fp[0];
    if (x >= xp[n - 1]) return fp[n - 1];
    while (hi - lo > 1) {
        mid = lo + (hi - lo) / 2;
        if (x >= xp[mid]) lo = mid; else hi = mid;
    }
    slope = (fp[lo + 1] - fp[lo]) / (xp[lo + 1] - xp[lo]);
    r = slope * (x - xp[lo]) + fp[lo];
    if (isnan(r)) {
        r = slope * (x - xp[lo + 1]) + fp[lo + 1];
        if (isnan(r) && fp[lo] == fp[lo + 1]) r = fp[lo];
    }
    return r;
}

/* scipy.special.ellipk(m) and ellipe(m), the complete elliptic integrals of the first and second
 * kind of parameter m <= 1, by the arithmetic-geometric mean (Abramowitz and Stegun 17.6.1-4):
 * K = pi / (2 M(1, sqrt(1 - m))), E = K (1 - sum_n 2^(n-1) c_n^2) with c_0^2 = m. NaN beyond 1. */
static double gw_agm(double m, double *weighted) {
    double a = 1.0, b = sqrt(1.0 - m), c, t, power = 0.5;
    int n;
    *weighted = 0.5 * m;
    for (n = 0; n < 64 && fabs(a - b) > 1e-16 * a; ++n) {
        c = 0.5 * (a - b);
        t = 0.5 * (a + b);
        b = sqrt(a * b);
        a = t;
        power *= 2.0;
        *weighted += power * c * c;
    }
    return a;
}

static double gw_ellipk(double m) {
    double weighted;
    if (isnan(m) || m > 1.0) return NAN;
    if (m == 1.0) return INFINITY;
    return GW_PI / (2.0 * gw_agm(m, &weighted));
}

static double gw_ellipe(double m) {
    double weighted, a;
    if (isnan(m) || m > 1.0) return NAN;
    if (m == 1.0) return 1.0;
    a = gw_agm(m, &weighted);
    return GW_PI / (2.0 * a) * (1.0 - weighted);
}

/* scipy.optimize.brentq's contract by Brent's method (Brent 1973, ch. 4), driven by the caller,
 * which evaluates f: the root lies between b and c; a is the previous b. Converged when f(b) is
 * 0 or the bracket's half-width is at most (xtol + rtol |b|) / 2. */
typedef struct { double a, b, c, fa, fb, fc, d, e, xtol, rtol; } gw_brent;

/* After f(b) is in fb: 1 when b is the root, else 0 with the next point to evaluate in b. */
static int gw_brent_step(gw_brent *z) {
    double tol, m, p, q, r, s;
    if ((z->fb > 0.0) == (z->fc > 0.0)) { /* the root left [b, c]: it is in [a, b] */
        z->c = z->a;
        z->fc = z->fa;
        z->d = z->e = z->b - z->a;
    }
    if (fabs(z->fc) < fabs(z->fb)) { /* b the best point */
        z->a = z->b; z->b = z->c; z->c = z->a;
        z->fa = z->fb; z->fb = z->fc; z->fc = z->fa;
    }
    tol = 0.5 * (z->xtol + z->rtol * fabs(z->b));
    m = 0.5 * (z->c - z->b);
    if (z->fb == 0.0 || fabs(m) <= tol) return 1;
    if (fabs(z->e) >= tol && fabs(z->fa) > fabs(z->fb)) {
        s = z->fb / z->fa;
        if (z->a == z->c) { /* secant */
            p = 2.0 * m * s;
            q = 1.0 - s;
        } else { /* inverse quadratic interpolation */
            q = z->fa / z->fc;
            r = z->fb / z->fc;
            p = s * (2.0 * m * q * (q - r) - (z->b - z->a) * (r - 1.0));
            q = (q - 1.0) * (r - 1.0) * (s - 1.0);
        }
        if (p > 0.0) q = -q; else p = -p;
        if (2.0 * p < fmin(3.0 * m * q - fabs(tol * q), fabs(z->e * q))) {
            z->e = z->d;
            z->d = p / q;
        } else { /* bisect */
            z->d = m;
            z->e = m;
        }
    } else {
        z->d = m;
        z->e = m;
    }
    z->a = z->b;
    z->fa = z->fb;
    z->b += fabs(z->d) > tol ? z->d : (m > 0.0 ? tol : -tol);
    return 0;
}

/* The start from a bracket [a, b] with fa = f(a), fb = f(b) of different signs (or a zero). */
static int gw_brent_start(gw_brent *z) {
    if (z->fa == 0.0) { z->b = z->a; z->fb = 0.0; return 1; }
    z->c = z->a;
    z->fc = z->fa;
    z->d = z->e = z->b - z->a;
    return gw_brent_step(z);
}

/* numpy.linalg.solve of a small system: Gaussian elimination with partial pivoting (the method
 * of LAPACK's dgesv, which numpy calls) of the n x n row-major a and the right-hand side b, both
 * overwritten, b with the solution. 1 when singular as LAPACK reports it (a pivot exactly 0). */
static int gw_solve(long n, double *a, double *b) {
    long i, j, k, p;
    double t;
    for (k = 0; k < n; ++k) {
        p = k;
        for (i = k + 1; i < n; ++i)
            if (fabs(a[i * n + k]) > fabs(a[p * n + k])) p = i;
        if (a[p * n + k] == 0.0) return 1;
        if (p != k) {
            for (j = 0; j < n; ++j) { t = a[k * n + j]; a[k * n + j] = a[p * n + j]; a[p * n + j] = t; }
            t = b[k]; b[k] = b[p]; b[p] = t;
        }
        for (i = k + 1; i < n; ++i) {
            t = a[i * n + k] / a[k * n + k];
            for (j = k + 1; j < n; ++j) a[i * n + j] -= t * a[k * n + j];
            b[i] -= t * b[k];
        }
    }
    for (i = n - 1; i >= 0; --i) {
        t = b[i];
        for (j = i + 1; j < n; ++j) t -= a[i * n + j] * b[j];
        b[i] = t / a[i * n + i];
    }
    return 0;
}

/* scipy.linalg.eigh(a, b, eigvals_only=True) of a small symmetric n x n a (row-major) and,
 * unless b is NULL, a symmetric positive definite b: b = L L^T (Cholesky), then the cyclic
 * Jacobi method on L^-1 a L^-T until every off-diagonal entry is below 1e-16 of the largest
 * diagonal one. The eigenvalues go to w in ascending order. a and b are overwritten; 1 when b
 * is not positive definite, else 0. */
static int gw_eigvalsh(long n, double *a, double *b, double *w) {
    long i, j, k, p, q, sweep;
    double t, c, s, theta, off, big, akp, akq;
    if (b) {
        for (j = 0; j < n; ++j) { /* b's lower triangle becomes L */
            t = b[j * n + j];
            for (k = 0; k < j; ++k) t -= b[j * n + k] * b[j * n + k];
            if (!(t > 0.0)) return 1;
            b[j * n + j] = sqrt(t);
            for (i = j + 1; i < n; ++i) {
                t = b[i * n + j];
                for (k = 0; k < j; ++k) t -= b[i * n + k] * b[j * n + k];
                b[i * n + j] = t / b[j * n + j];
            }
        }
        for (j = 0; j < n; ++j) /* a := L^-1 a, column by column (forward substitution) */
            for (i = 0; i < n; ++i) {
                t = a[i * n + j];
                for (k = 0; k < i; ++k) t -= b[i * n + k] * a[k * n + j];
                a[i * n + j] = t / b[i * n + i];
            }
        for (i = 0; i < n; ++i) /* a := a L^-T, row by row */
            for (j = 0; j < n; ++j) {
                t = a[i * n + j];
                for (k = 0; k < j; ++k) t -= a[i * n + k] * b[j * n + k];
                a[i * n + j] = t / b[j * n + j];
            }
    }
    for (sweep = 0; sweep < 100; ++sweep) {
        off = big = 0.0;
        for (i = 0; i < n; ++i) {
            big = fmax(big, fabs(a[i * n + i]));
            for (j = i + 1; j < n; ++j) off = fmax(off, fabs(a[i * n + j]));
        }
        if (!(off > 1e-16 * big)) break; /* a NaN stops too */
        for (p = 0; p < n; ++p)
            for (q = p + 1; q < n; ++q) {
                if (a[p * n + q] == 0.0) continue;
                theta = (a[q * n + q] - a[p * n + p]) / (2.0 * a[p * n + q]);
                t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
                c = 1.0 / sqrt(t * t + 1.0);
                s = t * c;
                for (k = 0; k < n; ++k) { /* columns p and q */
                    akp = a[k * n + p]; akq = a[k * n + q];
                    a[k * n + p] = c * akp - s * akq;
                    a[k * n + q] = s * akp + c * akq;
                }
                for (k = 0; k < n; ++k) { /* rows p and q */
                    akp = a[p * n + k]; akq = a[q * n + k];
                    a[p * n + k] = c * akp - s * akq;
                    a[q * n + k] = s * akp + c * akq;
                }
            }
    }
    for (i = 0; i < n; ++i) w[i] = a[i * n + i];
    for (i = 1; i < n; ++i) /* insertion sort, ascending */
        for (j = i; j > 0 && w[j - 1] > w[j]; --j) { t = w[j]; w[j] = w[j - 1]; w[j - 1] = t; }
    return 0;
}

#endif
