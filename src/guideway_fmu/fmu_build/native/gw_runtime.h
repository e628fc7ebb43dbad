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

typedef struct {
    char message[GW_MESSAGE_SIZE]; /* why the last translated call failed */
    size_t length;
} gw_ctx;

static void gw_msg_clear(gw_ctx *ctx) { ctx->length = 0; ctx->message[0] = '\0'; }

static void gw_msg_text(gw_ctx *ctx, const char *text) {
    size_t room = GW_MESSAGE_SIZE - 1 - ctx->length, n = strlen(text);
    if (n > room) n = room;
    memcpy(ctx->message + ctx->length, text, n);
    ctx->length += n;
    ctx->message[ctx->length] = '\0';
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

static double gw_mod(double a, double b) { /* Python's a % b: the sign of b */
    double r = fmod(a, b);
    if (r != 0.0 && ((r < 0.0) != (b < 0.0))) r += b;
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
static long gw_to_long(double x) { return isfinite(x) ? (long)x : 0; }

#endif
