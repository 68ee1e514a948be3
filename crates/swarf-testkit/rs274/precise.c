/*
 * precise.c: an LD_PRELOAD shim that makes LinuxCNC's standalone interpreter
 * `rs274 -g` print its canonical calls with 10 decimals instead of 4.
 *
 * rs274's canonical printer (sai/saicanon.cc) formats every coordinate with
 * "%.4f" through fprintf/printf, which the fortified glibc build turns into
 * __fprintf_chk / __printf_chk.  This library defines those two symbols,
 * copies the format string with each "%.4f" widened to "%.10f", and hands the
 * arguments on to vfprintf / vprintf.  Nothing else about the output changes:
 * the argument list is untouched (the conversion is still a double), so the
 * only difference is six more digits on each such number.
 *
 * Build:  gcc -shared -fPIC -O2 -o precise.so precise.c
 * Use:    LD_PRELOAD=/absolute/path/precise.so rs274 -g prog.ngc
 *
 * Written for swarf's G-code reference corpus (crates/swarf-nc/tests/corpus).
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Longest format we widen; longer ones (none in rs274) go through unchanged. */
#define WIDE_MAX 4096

/* Copies fmt into out with every "%.4f" replaced by "%.10f".  Returns out,
 * or fmt itself when it holds no "%.4f" or the result would not fit. */
static const char *widen(const char *fmt, char *out, size_t cap)
{
    if (fmt == NULL || strstr(fmt, "%.4f") == NULL)
        return fmt;
    size_t n = 0;
    for (const char *p = fmt; *p != '\0';) {
        if (strncmp(p, "%.4f", 4) == 0) {
            if (n + 5 >= cap)
                return fmt;
            memcpy(out + n, "%.10f", 5);
            n += 5;
            p += 4;
        } else {
            if (n + 1 >= cap)
                return fmt;
            out[n++] = *p++;
        }
    }
    out[n] = '\0';
    return out;
}

/* glibc's fortified fprintf: `flag` asks for extra checks, which we drop. */
int __fprintf_chk(FILE *stream, int flag, const char *fmt, ...)
{
    (void)flag;
    char buf[WIDE_MAX];
    va_list ap;
    va_start(ap, fmt);
    int r = vfprintf(stream, widen(fmt, buf, sizeof buf), ap);
    va_end(ap);
    return r;
}

/* glibc's fortified printf. */
int __printf_chk(int flag, const char *fmt, ...)
{
    (void)flag;
    char buf[WIDE_MAX];
    va_list ap;
    va_start(ap, fmt);
    int r = vprintf(widen(fmt, buf, sizeof buf), ap);
    va_end(ap);
    return r;
}
