/*
 * cclouds/fuzz/fuzz.h -- the byte reader shared by the libFuzzer harnesses: decodes the fuzz input into integers,
 * floats and choices. Floats are drawn half of the time from a table of edge values (NaN, +-Inf, +-0, denormals,
 * FLT_MAX, 2^24, values near the documented domain limits) and otherwise taken as raw IEEE bits, so the fuzzer
 * reaches NaN/Inf/huge values and domain edges quickly. A harness reads past the end of the input as zeros.
 */
#ifndef CCLOUDS_FUZZ_H
#define CCLOUDS_FUZZ_H

#include <assert.h> /* harnesses assert their own setup (asserts stay on in this build) */
#include <float.h>
#include <math.h>
#include <stddef.h> /* offsetof */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const uint8_t *data;
    size_t size;
    size_t pos;
} fz_reader;

static inline fz_reader fz_init(const uint8_t *data, size_t size) {
    fz_reader r;
    r.data = data;
    r.size = size;
    r.pos = 0;
    return r;
}

static inline uint8_t fz_u8(fz_reader *r) { return r->pos < r->size ? r->data[r->pos++] : 0; }

static inline uint32_t fz_u32(fz_reader *r) {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= (uint32_t)fz_u8(r) << (8 * i);
    return v;
}

static inline int fz_bool(fz_reader *r) { return fz_u8(r) & 1; }

/* An int32: edge values (0, +-1, INT32_MIN/MAX, ...) or small values near the interesting range, or raw bits. */
static inline int32_t fz_i32(fz_reader *r) {
    static const int32_t edges[] = {0, 1, -1, 2, 3, 4, 5, 7, 8, 16, 31, 32, 33, 64, 255, 256, 4096, 4097, 65536,
                                    INT32_MAX, INT32_MIN, INT32_MAX - 1, INT32_MIN + 1, 0x3FFFFFFF, 0x40000000};
    uint8_t k = fz_u8(r);
    if (k < 96) return edges[k % (sizeof edges / sizeof edges[0])];
    if (k < 192) return (int32_t)(int8_t)fz_u8(r);
    uint32_t u = fz_u32(r);
    int32_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

/* An int in [lo, hi] (inclusive). */
static inline int32_t fz_range(fz_reader *r, int32_t lo, int32_t hi) {
    uint32_t span = (uint32_t)((int64_t)hi - (int64_t)lo + 1);
    return (int32_t)((int64_t)lo + (int64_t)(fz_u32(r) % span));
}

/* A float: an edge value, a small "sane" value, or raw bits. */
static inline float fz_float(fz_reader *r) {
    static const float edges[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, 2.0f, 10.0f, 0.25f, 0.125f, 1e-3f, 1e-6f, 1e-30f,
                                  1e-45f, FLT_MIN, FLT_MAX, -FLT_MAX, 16777216.0f, 8388608.0f, 1e6f, 1e10f, 1e30f,
                                  -1e30f, 3.14159265f, 1.57079633f, 6371.0f, 100000.0f, 0.999f, 1.001f, 255.0f,
                                  256.0f, 4096.0f, -0.5f, -2.0f};
    uint8_t k = fz_u8(r);
    if (k < 16) return NAN;
    if (k < 24) return INFINITY;
    if (k < 32) return -INFINITY;
    if (k < 128) return edges[k % (sizeof edges / sizeof edges[0])];
    if (k < 192) return (float)(int16_t)fz_u32(r) / 256.0f; /* in [-128, 128) in 1/256 steps */
    uint32_t u = fz_u32(r);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* A finite float in [lo, hi] (uniform 16-bit grid). */
static inline float fz_unit(fz_reader *r, float lo, float hi) {
    uint32_t u = fz_u32(r) & 0xFFFFu;
    return lo + (hi - lo) * ((float)u / 65535.0f);
}

/* Abort with a message: the contract of the function under test was broken (libFuzzer records the input). */
#define FZ_CHECK(cond, ...)                                                                                          \
    do {                                                                                                             \
        if (!(cond)) {                                                                                               \
            fprintf(stderr, "contract violated at %s:%d: %s\n  ", __FILE__, __LINE__, #cond);                        \
            fprintf(stderr, __VA_ARGS__);                                                                            \
            fprintf(stderr, "\n");                                                                                   \
            abort();                                                                                                 \
        }                                                                                                            \
    } while (0)

static inline int fz_all_finite(const float *v, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static inline int fz_all_in(const float *v, size_t n, float lo, float hi) {
    for (size_t i = 0; i < n; ++i)
        if (!(v[i] >= lo && v[i] <= hi)) return 0;
    return 1;
}


/* Mutating a struct: a table of its scalar fields (offset, 'f' float or 'i' int32), and a few fields overwritten
 * with decoded values (floats: edge values or raw bits; ints: edge values, small values or raw bits). */
typedef struct {
    size_t offset;
    char kind;
} fz_field;

#define FZ_F(type, member) {offsetof(type, member), 'f'}
#define FZ_I(type, member) {offsetof(type, member), 'i'}
#define FZ_V3(type, member)                                                                                          \
    {offsetof(type, member), 'f'}, {offsetof(type, member) + sizeof(float), 'f'},                                    \
        {offsetof(type, member) + 2 * sizeof(float), 'f'}

static inline void fz_mutate(fz_reader *r, void *s, const fz_field *fields, size_t n, int max_changes) {
    int changes = fz_u8(r) % (max_changes + 1);
    for (int k = 0; k < changes; ++k) {
        const fz_field *f = &fields[fz_u8(r) % n];
        unsigned char *p = (unsigned char *)s + f->offset;
        if (f->kind == 'f') {
            float v = fz_float(r);
            memcpy(p, &v, sizeof v);
        } else {
            int32_t v = fz_i32(r);
            memcpy(p, &v, sizeof v);
        }
    }
}

/* Print the fields of a mutated struct that differ from a reference (to read a finding). */
static inline void fz_print_changed(const void *s, const void *ref, const fz_field *fields, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        const unsigned char *a = (const unsigned char *)s + fields[i].offset;
        const unsigned char *b = (const unsigned char *)ref + fields[i].offset;
        if (memcmp(a, b, 4) == 0) continue;
        if (fields[i].kind == 'f') {
            float v;
            memcpy(&v, a, sizeof v);
            fprintf(stderr, "  field #%zu (offset %zu) = %.9g\n", i, fields[i].offset, (double)v);
        } else {
            int32_t v;
            memcpy(&v, a, sizeof v);
            fprintf(stderr, "  field #%zu (offset %zu) = %d\n", i, fields[i].offset, (int)v);
        }
    }
}

#endif /* CCLOUDS_FUZZ_H */
