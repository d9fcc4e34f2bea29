/* numparse.h - text to numbers in one fixed grammar, whatever the locale.
 * strtod follows LC_NUMERIC: under de_DE it stops at the '.' of "0.5"
 * (and reads "0,5"), and a host application such as Blender may set the
 * locale of the process the library runs in. Every text-to-number
 * conversion of the library and the CLI goes through here. */
#ifndef BANYAN_NUMPARSE_H
#define BANYAN_NUMPARSE_H

#include <stddef.h>
#include <stdint.h>

/* A decimal number at the start of s: [+-]D[.D][(e|E)[+-]D] where D is
 * one or more digits, one side of the '.' may be empty. No leading space,
 * no hexadecimal, inf or nan. Returns the bytes read (0: no number; *out
 * untouched) and *out, rounded as strtod rounds in the C locale
 * (+-HUGE_VAL past the double range, 0 below it). */
size_t num_scan_double(const char *s, double *out);

/* The whole of s is one such number. 1 on success, else 0. */
int num_parse_double(const char *s, double *out);

/* The whole of s is a base-10 integer within [lo, hi]: digits only, with a
 * leading '-' only when lo < 0; no '+', no space. 1 on success, else 0. */
int num_parse_int(const char *s, long long lo, long long hi, long long *out);

/* The whole of s is a base-10 integer within [0, 2^64-1], digits only. */
int num_parse_u64(const char *s, uint64_t *out);

#endif
