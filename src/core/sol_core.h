/* sol_core.h - status codes, images and image files shared by every sol module.
 *
 * Conventions of the whole library (every module follows them):
 *  - Every fallible function returns a sol_status; SOL_OK is zero.
 *  - On error the caller's output buffers are left untouched.
 *  - The library never prints, exits or aborts.
 *  - Buffers are caller-owned, or freed with the module's explicit *_free function.
 *  - Option structs are zero-initialised by the caller; a zero field means "default".
 */
#ifndef SOL_CORE_H
#define SOL_CORE_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Version of this header (semantic versioning); sol_version() gives the library's, so a program
 * can check that the library it loaded matches the header it was built with. */
#define SOL_VERSION_MAJOR 0
#define SOL_VERSION_MINOR 1
#define SOL_VERSION_PATCH 0
#define SOL_VERSION_STRING "0.1.0"
/* The library's version string ("0.1.0"), static, never NULL. */
const char *sol_version(void);

typedef enum sol_status {
    SOL_OK = 0,
    SOL_ERR_NULL_ARG,       /* a required pointer was NULL */
    SOL_ERR_INVALID_ARG,    /* an argument is outside its documented domain */
    SOL_ERR_NONFINITE,      /* an input value is NaN or infinite */
    SOL_ERR_ZERO_LENGTH,    /* a vector that must have a direction has length zero */
    SOL_ERR_OUT_OF_RANGE,   /* a value cannot be represented by the target format */
    SOL_ERR_NO_MEMORY,      /* an allocation failed */
    SOL_ERR_IO,             /* a file could not be opened, read or written */
    SOL_ERR_FORMAT,         /* a file is malformed or of an unsupported kind */
    SOL_ERR_UNSUPPORTED,    /* the request is valid but this build does not support it */
    SOL_ERR_NO_CONVERGENCE, /* an iterative method did not reach its tolerance */
    SOL_ERR_SOLVER,         /* an external solver (Ceres) reported failure */
    SOL_ERR_LIMIT,          /* an input asks for more than the caller's (or default) work/size limit */
    SOL_STATUS_COUNT
} sol_status;

/* A short, static, human-readable description ("invalid argument").
 * Never NULL; unknown values give "unknown status". */
const char *sol_status_string(sol_status status);

/* Interleaved float image, row-major, `channels` values per pixel.
 * 8- and 16-bit files load as code / (2^bits - 1); EXR loads its values as they are. */
typedef struct sol_image {
    int width;
    int height;
    int channels; /* 1..4 */
    float *data;  /* width * height * channels values */
} sol_image;

/* Allocates a zero-filled image. `out` is written only on success. */
sol_status sol_image_alloc(sol_image *out, int width, int height, int channels);
/* Frees the pixels and zeroes the struct; safe on a zeroed or NULL image. */
void sol_image_free(sol_image *image);
/* Pointer to pixel (x, y); no bounds check. */
static inline float *sol_image_pixel(const sol_image *image, int x, int y)
{
    return image->data + ((size_t)y * (size_t)image->width + (size_t)x) * (size_t)image->channels;
}

/* ---- limits for untrusted input ----
 * Every reader sizes its allocations from the file's header, so every reader first checks the
 * header's sizes against a limit: a 99-byte PNG may claim 16.7 GB. A zero field means the default.
 * Readers that refuse a file for its size return SOL_ERR_LIMIT and allocate nothing. */
#define SOL_READ_MAX_PIXELS_DEFAULT ((uint64_t)1 << 27) /* 134M pixels: 16384 x 8192 */
#define SOL_READ_MAX_BYTES_DEFAULT ((uint64_t)1 << 31)  /* 2 GiB of decoded data */
typedef struct sol_read_limits {
    uint64_t max_pixels; /* width * height (* depth); 0: SOL_READ_MAX_PIXELS_DEFAULT */
    uint64_t max_bytes;  /* bytes the reader will allocate for the decoded data; 0: default */
} sol_read_limits;

/* Overflow-checked size arithmetic: *out = a * b; returns 0 (and leaves *out alone) on overflow. */
static inline int sol_size_mul(size_t *out, size_t a, size_t b)
{
    if (a != 0 && b > SIZE_MAX / a)
        return 0;
    *out = a * b;
    return 1;
}

/* Checks a decoded size against `limits` (NULL: the defaults): SOL_OK, SOL_ERR_INVALID_ARG for a
 * non-positive dimension, SOL_ERR_LIMIT when pixels = width*height*depth or bytes =
 * pixels*bytes_per_pixel exceeds its limit or overflows. */
sol_status sol_read_limits_check(const sol_read_limits *limits, int64_t width, int64_t height, int64_t depth,
                                 uint64_t bytes_per_pixel);

/* ---- atomic file output (every writer of sol uses it) ----
 * sol_file_out_open creates a new temporary file "<folder of path>/.sol-tmp-<pid>-<n>" (O_EXCL,
 * mode 0666 less the umask, as fopen) and opens it for writing in out->file; nothing exists at
 * `path` yet. sol_file_out_close(out, 1) flushes, fsyncs and closes it and renames it over `path`
 * (atomic within one file system): SOL_OK only if every step succeeded (so a write error that
 * stdio buffered, e.g. a full disk, is still reported), else SOL_ERR_IO. sol_file_out_close(out,
 * 0) discards: closes and removes the temporary and returns SOL_OK. Either way the temporary is
 * gone afterwards and `*out` is zeroed. A `path` naming an existing device or FIFO (which a
 * rename cannot replace) is opened and written in place instead; a directory is SOL_ERR_IO; a
 * symbolic link at `path` is replaced by the new file (its target is left alone).
 * Errors of open: SOL_ERR_NULL_ARG, SOL_ERR_IO (empty path, folder missing or not writable),
 * SOL_ERR_NO_MEMORY; `*out` is untouched on error. `path` must stay valid until the close. */
typedef struct sol_file_out {
    FILE *file;      /* write here (stdio) */
    char *temp_path; /* the temporary's name; NULL when writing a device in place */
    const char *path;
} sol_file_out;
sol_status sol_file_out_open(sol_file_out *out, const char *path);
sol_status sol_file_out_close(sol_file_out *out, int commit);

/* PNG through libpng. Reading accepts gray, gray+alpha, RGB, RGBA and palette files of any bit
 * depth (expanded to 8 or 16 bits, then normalised), progressive or Adam7-interlaced. Writing
 * quantises each value v in [0,1] to round(v * (2^bits - 1)) with bits 8 or 16; values outside
 * [0,1] give SOL_ERR_OUT_OF_RANGE and NaN/Inf give SOL_ERR_NONFINITE (nothing is written).
 * `bits_out` may be NULL.
 * Reading checks the header's width x height against `limits` (sol_png_read: the defaults) before
 * allocating anything, counting 4 bytes per float value plus, for an interlaced file, the raw
 * image libpng decodes into (channels * bits/8 bytes per pixel): SOL_ERR_LIMIT. A missing or
 * unreadable file is SOL_ERR_IO, a malformed, truncated or corrupt one SOL_ERR_FORMAT; whatever
 * the error, everything the read allocated is freed and `*out` / `*bits_out` are untouched.
 * Writing goes to a temporary file in the same folder, renamed over `path` on success; on any
 * error (SOL_ERR_IO for a failed open, write, flush or rename) no temporary is left and `path` is
 * as it was (absent, or the old file unchanged). */
sol_status sol_png_read(const char *path, sol_image *out, int *bits_out);
sol_status sol_png_read_ex(const char *path, const sol_read_limits *limits, sol_image *out, int *bits_out);
sol_status sol_png_write(const char *path, const sol_image *image, int bits);

/* OpenEXR through its C core API (scanline files, any compression the core reads).
 * Channels are read by name: Y (1), Y/A (2), R,G,B (3), R,G,B,A (4); half and float both load
 * as float. Writing stores half (`half_precision` != 0, values must fit half: |v| <= 65504,
 * else SOL_ERR_OUT_OF_RANGE) or float, ZIP-compressed. NaN/Inf are refused with
 * SOL_ERR_NONFINITE. */
sol_status sol_exr_read(const char *path, sol_image *out);
/* Reading checks the data window against `limits` (sol_exr_read: the defaults) before anything
 * is sized from it: width x height pixels at 8 bytes per kept channel (sol's image and its
 * decoding planes), and width x min(scanlines per chunk, height) pixels at twice the bytes of all
 * the file's channels (the core's chunk buffers); a file with more than SOL_EXR_MAX_CHANNELS
 * channels is refused too. Any of these gives SOL_ERR_LIMIT; a missing or unreadable file SOL_ERR_IO, a
 * malformed one SOL_ERR_FORMAT. On every error all memory is freed and `*out` is untouched.
 * Writing goes to a temporary file in the same folder, renamed over `path` on success (on error
 * no temporary is left and `path` is as it was). */
#define SOL_EXR_MAX_CHANNELS 1024
sol_status sol_exr_read_ex(const char *path, const sol_read_limits *limits, sol_image *out);
sol_status sol_exr_write(const char *path, const sol_image *image, int half_precision);

/* ---- DDS block-compressed textures (read side; sol writes them in src/normalmaps/dds.c) ----
 * The container is in core because two modules decode its blocks: textures (BC1) and normalmaps
 * (BC4/BC5). Reads the top mip level of a 2D texture: the 128-byte DirectDraw Surface header with
 * FourCC "DXT1" (BC1), "ATI1"/"BC4U" (BC4), "ATI2"/"BC5U" (BC5), or "DX10" with its 20-byte
 * extension and DXGI format 71/72 (BC1), 80 (BC4_UNORM), 83 (BC5_UNORM). Blocks are kept as
 * stored (row-major block order, 8 or 16 bytes each). Sizes are checked with
 * sol_read_limits_check (decoded RGBA8) before anything is allocated.
 * Errors: SOL_ERR_FORMAT (not a DDS, wrong header sizes, truncated data), SOL_ERR_UNSUPPORTED
 * (another FourCC/DXGI format, cube maps, volumes), SOL_ERR_LIMIT, SOL_ERR_IO, SOL_ERR_NO_MEMORY;
 * *problem (may be NULL) then names what was wrong (static string). Free with sol_dds_free. */
typedef enum sol_dds_format { SOL_DDS_BC1 = 1, SOL_DDS_BC4, SOL_DDS_BC5 } sol_dds_format;
typedef struct sol_dds {
    sol_dds_format format;
    int width, height;
    size_t size;     /* bytes of blocks: ceil(w/4) * ceil(h/4) * (8 for BC1/BC4, 16 for BC5) */
    uint8_t *blocks; /* owned */
} sol_dds;
sol_status sol_dds_parse(const uint8_t *data, size_t size, const sol_read_limits *limits, sol_dds *out,
                         const char **problem);
sol_status sol_dds_read(const char *path, const sol_read_limits *limits, sol_dds *out, const char **problem);
/* Frees the blocks and zeroes the struct; safe on NULL or a zeroed struct. */
void sol_dds_free(sol_dds *dds);

/* Reads a whole file into a new buffer (NUL-terminated for text parsers; *size excludes the NUL).
 * Files larger than max_bytes (0: SOL_READ_MAX_BYTES_DEFAULT) give SOL_ERR_LIMIT.
 * Errors: SOL_ERR_NULL_ARG, SOL_ERR_IO, SOL_ERR_LIMIT, SOL_ERR_NO_MEMORY. Free with free(). */
sol_status sol_file_read_all(const char *path, uint64_t max_bytes, uint8_t **data, size_t *size);

/* ---- small shared numeric helpers (header-only so hot loops inline them) ---- */

static inline double sol_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* sol_angle3 with both vectors first divided by their largest absolute component and |a x b|
 * taken the same way, so nothing overflows or underflows (sol_angle3's path for extreme
 * magnitudes; callable directly). */
static inline double sol_angle3_scaled(const double a[3], const double b[3])
{
    double ma = fmax(fmax(fabs(a[0]), fabs(a[1])), fabs(a[2]));
    double mb = fmax(fmax(fabs(b[0]), fabs(b[1])), fabs(b[2]));
    if (!(ma > 0.0) || !(mb > 0.0))
        /* a zero vector; fmax skipped any NaN, and x * 0 is 0 only for finite x */
        return a[0] * 0.0 + a[1] * 0.0 + a[2] * 0.0 + b[0] * 0.0 + b[1] * 0.0 + b[2] * 0.0 == 0.0 ? 0.0 : NAN;
    /* divisions, not a reciprocal: 1/ma overflows for a subnormal ma */
    double a0 = a[0] / ma, a1 = a[1] / ma, a2 = a[2] / ma, b0 = b[0] / mb, b1 = b[1] / mb, b2 = b[2] / mb;
    double c0 = a1 * b2 - a2 * b1, c1 = a2 * b0 - a0 * b2, c2 = a0 * b1 - a1 * b0;
    double mc = fmax(fmax(fabs(c0), fabs(c1)), fabs(c2)), cross = 0.0;
    if (mc > 0.0) {
        c0 /= mc, c1 /= mc, c2 /= mc;
        cross = mc * sqrt(c0 * c0 + c1 * c1 + c2 * c2);
    }
    return atan2(cross, a0 * b0 + a1 * b1 + a2 * b2);
}

/* Angle between two non-zero vectors in radians, accurate near 0 and pi: atan2(|a x b|, a.b)
 * (acos of a clamped dot loses half the digits for nearly parallel vectors). Unnormalised input
 * of any finite magnitude is fine (1e-300 and 1e300 alike): when a vector's largest component is
 * outside [2^-200, 2^200], or |a x b|^2 would underflow (angles below ~1e-120 rad at unit
 * length), it takes the scaled path sol_angle3_scaled; otherwise the direct formula (no
 * divisions). A zero vector gives 0; a NaN or infinite component gives NaN. */
static inline double sol_angle3(const double a[3], const double b[3])
{
    double ma = fmax(fmax(fabs(a[0]), fabs(a[1])), fabs(a[2]));
    double mb = fmax(fmax(fabs(b[0]), fabs(b[1])), fabs(b[2]));
    if (ma >= 0x1p-200 && ma <= 0x1p200 && mb >= 0x1p-200 && mb <= 0x1p200) {
        double c0 = a[1] * b[2] - a[2] * b[1], c1 = a[2] * b[0] - a[0] * b[2], c2 = a[0] * b[1] - a[1] * b[0];
        double s = c0 * c0 + c1 * c1 + c2 * c2;
        if (s >= 0x1p-900 || (c0 == 0.0 && c1 == 0.0 && c2 == 0.0)) /* NaN fails both: scaled path */
            return atan2(sqrt(s), sol_dot3(a, b));
    }
    return sol_angle3_scaled(a, b);
}

/* UNORM quantisation as D3D/GL define it: code = round(clamp(x,0,1) * (2^bits - 1)), and back.
 * NaN encodes as 0 (D3D's float-to-UNORM rule). bits 1..32; any other `bits` encodes to 0 and
 * decodes to 0.0 (there is no such format; no shift past the word is ever made). */
static inline uint32_t sol_unorm_encode(double x, int bits)
{
    if (bits < 1 || bits > 32)
        return 0;
    double maxcode = (double)(UINT32_MAX >> (32 - bits));
    if (!(x > 0.0))
        return 0;
    if (x >= 1.0)
        return (uint32_t)maxcode;
    return (uint32_t)floor(x * maxcode + 0.5);
}

static inline double sol_unorm_decode(uint32_t code, int bits)
{
    if (bits < 1 || bits > 32)
        return 0.0;
    return (double)code / (double)(UINT32_MAX >> (32 - bits));
}

/* sRGB transfer functions (IEC 61966-2-1): linear <-> encoded, input clamped to [0, 1] (NaN
 * gives 0). The one sRGB curve of the library: textures' SOL_TRANSFER_SRGB and hdr's display
 * codes both use it. */
double sol_srgb_encode(double linear);
double sol_srgb_decode(double encoded);

/* Deterministic pseudo-random numbers: SplitMix64 (Steele, Lea, Flood, "Fast splittable
 * pseudorandom number generators", OOPSLA 2014). The whole state is one uint64_t, so a parallel
 * loop can give every item its own stream (seed = item index) and stay thread-count independent. */
static inline uint64_t sol_mix64(uint64_t counter) /* the SplitMix64 output for one counter value */
{
    uint64_t z = counter + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static inline uint64_t sol_rng_next(uint64_t *state)
{
    uint64_t counter = *state;
    *state += 0x9E3779B97F4A7C15ull;
    return sol_mix64(counter);
}

/* Uniform double in [lo, hi) with 53 random bits. */
static inline double sol_rng_uniform(uint64_t *state, double lo, double hi)
{
    return lo + (hi - lo) * (double)(sol_rng_next(state) >> 11) * 0x1.0p-53;
}

/* Low-discrepancy points: the n-th point of the 2D Hammersley-free R2 sequence
 * (Roberts 2018, additive recurrence with the plastic constant), in [0,1)^2.
 * Deterministic, usable from parallel loops (no state). */
void sol_r2_point(uint64_t n, double *u, double *v);
/* Maps (u, v) in [0,1)^2 to a uniformly distributed unit vector (equal-area cylinder map). */
void sol_sphere_uniform(double u, double v, double dir[3]);

#ifdef __cplusplus
}
#endif
#endif
