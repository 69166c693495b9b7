/* encodings.h - what the files of the d6_d7_s1_s5_normal_encodings driver share. */
#ifndef ENCODINGS_H
#define ENCODINGS_H
#include "exp_harness.h"
#include "sol_normals.h"

#define DEG (180.0 / M_PI)

/* The i-th direction of the driver's R2 set (uniform on the sphere). */
void r2_direction(uint64_t i, double d[3]);

/* Error statistics in degrees of `n` errors (the array is reordered). */
typedef struct error_stats {
    double mean, rms, p99, max;
} error_stats;
error_stats stats_of(float *err, size_t n);
/* Bits a uniform quantizer of the sphere would need for the same RMS error: cells of area
 * 4 pi / N treated as discs, whose RMS radius is r / sqrt(2), give N = 2 / rms^2. */
double effective_bits(double rms_deg);

/* An encoder seen as a function, so error loops and timings treat all paths alike. */
typedef struct encoder {
    const char *name;
    sol_normal_method method;          /* for the generic path; decode method for tables */
    const sol_bestfit_table *table;    /* non-NULL: baked-table path */
    sol_table_filter filter;
} encoder;
uint32_t encode_with(const encoder *e, const double n[3]);
void decode_with(const encoder *e, uint32_t code, double n[3]);
/* Angular errors (degrees) of an encoder over R2 directions [0, n), in parallel. */
void encoder_errors(const encoder *e, size_t n, float *err);

void run_d6_table(const exp_run *exp);
void run_d7_blending(const exp_run *exp);
/* S5: octahedral bit sweep and L. Tyler's tables side by side (oct_sweep.c). */
void run_oct_sweep(const exp_run *exp);
/* --bench only: the octahedral map's bits, rounding and quantizer, error vs time with 24-bit peers. */
void run_oct_bench(const exp_run *exp);
#endif
