/* Test only (isa_sweep.py): loaded with LD_PRELOAD in front of Embree, it
 * appends $BANYAN_TEST_EMBREE_CONFIG (e.g. "isa=sse2,verbose=1") to every
 * rtcNewDevice configuration, so one machine runs the library on each of
 * Embree's kernel sets as CPUs without the newer ones would. The library
 * itself has no such knob. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

typedef void *(*new_device_fn)(const char *);

void *rtcNewDevice(const char *config);

void *rtcNewDevice(const char *config) {
    new_device_fn real;
    *(void **)&real = dlsym(RTLD_NEXT, "rtcNewDevice"); /* POSIX's way round ISO C's object/function split */
    if (!real) {
        fprintf(stderr, "embree_isa_preload: no rtcNewDevice after this library\n");
        abort();
    }
    const char *extra = getenv("BANYAN_TEST_EMBREE_CONFIG");
    if (!extra || !*extra) return real(config);
    char buf[1024];
    int n = snprintf(buf, sizeof buf, "%s%s%s", config ? config : "", config && *config ? "," : "", extra);
    if (n < 0 || (size_t)n >= sizeof buf) {
        fprintf(stderr, "embree_isa_preload: configuration too long\n");
        abort();
    }
    return real(buf);
}
