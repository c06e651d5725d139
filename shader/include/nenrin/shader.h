/*
 * nenrin/shader.h: the C ABI of nenrin's wood shader, for renderers that load it as a plugin
 * (libnenrin_shader.so, typically through dlopen). See docs/plugin.md.
 *
 * Pure C (C89 and later, or C++): an opaque shader handle created from a JSON description,
 * a batch evaluation of tree-space points, and destruction. No entry point throws, aborts or
 * exits: every failure is a nenrin_status plus a human-readable message.
 *
 * Units and frame: tree space, metres, right-handed, +Z up the trunk (the trunk grows along +Z
 * from the skeleton's first point, usually the origin). Growth time T is in years.
 *
 * Messages: every function that takes `message` / `message_size` writes a NUL-terminated
 * UTF-8 string of at most message_size bytes (including the NUL), truncated if longer: the
 * error on failure, "" on success. `message` may be NULL (or message_size 0): nothing is
 * written then.
 *
 * ABI versioning: NENRIN_SHADER_ABI_VERSION changes whenever a signature, the status values or
 * the layout of nenrin_shading_result change. A host compiled against this header should
 * check nenrin_shader_abi_version() == NENRIN_SHADER_ABI_VERSION after loading the library.
 */
#ifndef NENRIN_SHADER_H
#define NENRIN_SHADER_H

#include <stddef.h>

/* Symbols the shared library exports; everything else in it is hidden. */
#if defined(_WIN32)
#define NENRIN_SHADER_API
#elif defined(__GNUC__) && __GNUC__ >= 4
#define NENRIN_SHADER_API __attribute__((visibility("default")))
#else
#define NENRIN_SHADER_API
#endif

/* The ABI this header describes. */
#define NENRIN_SHADER_ABI_VERSION 1

#ifdef __cplusplus
extern "C" {
#endif

/* A wood shader: a tree (skeleton), its grain parameters and a finish, ready to evaluate.
 * Immutable after creation: any number of threads may evaluate one shader at once. */
typedef struct nenrin_shader nenrin_shader;

typedef enum nenrin_status {
    NENRIN_OK = 0,
    /* A NULL or out-of-range argument, or a NaN / infinite point or footprint. */
    NENRIN_ERROR_INVALID_ARGUMENT = 1,
    /* Bad input: malformed JSON, an unknown key, a value out of range, a file that cannot be
     * read. The message names the file (or "<description>"), the JSON path or line and
     * column, and what was expected, like every nenrin error. */
    NENRIN_ERROR_INPUT = 2,
    /* Out of memory, or a failure inside nenrin or its libraries (e.g. Embree). */
    NENRIN_ERROR_INTERNAL = 3
} nenrin_status;

/* The surface response at one point. All values are single precision. */
typedef struct nenrin_shading_result {
    /* Diffuse albedo of the wood, scene-linear Rec.709 primaries, each >= 0 (and below 1 for
     * sensible grain colours). The ring profile is box-filtered over the footprint; black
     * where coverage is 0. */
    float albedo[3];
    /* GGX alpha (not perceptual roughness) of the finish's clear coat, or of the bare wood
     * for a finish without a coat. The same for every point of one shader. */
    float roughness;
    /* Unit fibre direction in tree space (for anisotropic highlights): the growth axis (the
     * branch's axis inside a knot), bent into the ring surface so that it flows around knots.
     * Its sign carries no meaning. */
    float fibre[3];
    /* Growth time, years: when the bark reached this point. Rings are iso-surfaces of T
       (inside knots with a ring wobble, late_wood follows the drawn rings, T does not). */
    float T;
    /* Share of branch paths in the junction blend, 0..1: 0 in clear wood, 1 inside a knot. */
    float knot;
    /* Part of `knot` from branches that had died before the trunk enclosed the point (loose,
     * dark dead knots), 0..knot. */
    float dead_knot;
    /* 1 inside the felled log, 0 outside it (T past the grain's felling_time): treat as alpha
     * / a cut-out mask. Always 1 when the grain has no felling time. */
    float coverage;
    /* Late-wood share of the ring profile (E of Momoi's eq. 6), 0 (early wood) .. 1 (late
     * wood), filtered over the footprint: useful as a bump or roughness mask. */
    float late_wood;
} nenrin_shading_result;

/* NENRIN_SHADER_ABI_VERSION of the loaded library. */
NENRIN_SHADER_API int nenrin_shader_abi_version(void);

/* nenrin's version, e.g. "0.1.0". A static string: do not free. */
NENRIN_SHADER_API const char* nenrin_shader_version(void);

/* Creates a shader from a JSON description (UTF-8, NUL-terminated):
 *
 *   { "skeleton": "trees/conifer.json" or an inline skeleton object (required),
 *     "grain":    "grain/species/norway-spruce.json"  or an inline grain object (optional: built-in
 * defaults), "finish":   "matte" | "oiled" | "varnished" (optional, default "oiled") }
 *
 * Skeleton and grain objects use the formats of docs/skeleton-format.md and
 * docs/grain-format.md. Unknown keys, here and in those objects, are errors. Relative file
 * names are resolved against `base_directory`, or against the current directory if it is NULL
 * or "".
 *
 * On success *out holds the new shader (free it with nenrin_shader_destroy); on failure *out is
 * set to NULL (if out is not NULL). Statuses: NENRIN_ERROR_INVALID_ARGUMENT (json_description
 * or out NULL), NENRIN_ERROR_INPUT, NENRIN_ERROR_INTERNAL. Creation builds spatial indices: do it
 * once per tree, not per frame. Safe to call from several threads at once. */
NENRIN_SHADER_API nenrin_status nenrin_shader_create(const char* json_description,
                                                     const char* base_directory,
                                                     nenrin_shader** out, char* message,
                                                     size_t message_size);

/* Evaluates `count` tree-space points:
 *   points      3 * count floats, x y z of each point, metres;
 *   footprints  NULL (point samples) or count floats: the diameter (metres, >= 0) of the
 *               surface area each point stands for (e.g. a pixel's footprint). The ring profile
 *               is filtered over it so that distant wood shows no moire; 0 = a point sample;
 *   out         count results.
 *
 * Every point and footprint is checked first: a NaN or infinite coordinate, or a NaN, infinite
 * or negative footprint, gives NENRIN_ERROR_INVALID_ARGUMENT with a message naming its index,
 * and nothing is written to out (nor after any other NENRIN_ERROR_INVALID_ARGUMENT; after
 * NENRIN_ERROR_INTERNAL its contents are unspecified). count 0 succeeds (points, footprints and
 * out may then be NULL). Results do not depend on how points are batched, but
 * spatially coherent batches (neighbouring pixels next to each other) are much faster than
 * scattered ones, and large batches amortise the per-call cost.
 *
 * Thread-safe: any number of threads may evaluate the same shader at once. */
NENRIN_SHADER_API nenrin_status nenrin_shader_evaluate(const nenrin_shader* shader, size_t count,
                                                       const float* points, const float* footprints,
                                                       nenrin_shading_result* out, char* message,
                                                       size_t message_size);

/* Frees a shader. NULL is accepted and ignored. No evaluation may be running on it. */
NENRIN_SHADER_API void nenrin_shader_destroy(nenrin_shader* shader);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* NENRIN_SHADER_H */
