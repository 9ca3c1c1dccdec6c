/* SPDX-License-Identifier: MIT */
#ifndef URBANPVS_URBANPVS_H
#define URBANPVS_URBANPVS_H

/*
 * C API of the urbanpvs runtime: load a .pvs file, locate a point in a view cell, get the
 * objects visible from it. A thin layer over urbanpvs::runtime::PvsFile (C++17), for engines
 * that bind C. Plain types only; every function returns a status (or a value documented below)
 * and never aborts.
 *
 * Safety on untrusted input: urbanpvs_open_* validate the whole file (header, checksums, every
 * count, offset, string and encoded PVS) before they succeed; after that no call reads outside
 * the buffer. The loader is fuzzed.
 *
 * Thread safety: a successfully opened urbanpvs_file may be queried from any number of threads
 * at once; urbanpvs_close must not race with queries.
 *
 * Ownership: urbanpvs_open_memory borrows the caller's buffer, which must stay alive and
 * unchanged until urbanpvs_close; urbanpvs_open_file owns its bytes. Strings returned point into
 * the file's bytes and are valid until urbanpvs_close; they are UTF-8 and NOT NUL-terminated.
 */

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Same values as urbanpvs::runtime::Status. */
typedef enum urbanpvs_status {
  URBANPVS_OK = 0,
  URBANPVS_BAD_MAGIC = 1,
  URBANPVS_UNSUPPORTED_VERSION = 2,
  URBANPVS_UNSUPPORTED_FEATURE = 3,
  URBANPVS_TRUNCATED = 4,
  URBANPVS_TRAILING_BYTES = 5,
  URBANPVS_HEADER_CHECKSUM_MISMATCH = 6,
  URBANPVS_SECTION_CHECKSUM_MISMATCH = 7,
  URBANPVS_MALFORMED_HEADER = 8,
  URBANPVS_MISSING_SECTION = 9,
  URBANPVS_MALFORMED_SECTION = 10,
  URBANPVS_OUT_OF_RANGE = 11,
  URBANPVS_BUFFER_TOO_SMALL = 12,
  URBANPVS_OUT_OF_MEMORY = 13,
  URBANPVS_IO_ERROR = 14,
  URBANPVS_NOT_GEOGRAPHIC = 15,
  URBANPVS_INVALID_ARGUMENT = 16,
  URBANPVS_NOT_EXPANDED = 17
} urbanpvs_status;

/* Flags of urbanpvs_open_file_flags. */
#define URBANPVS_OPEN_EXPAND_PVS 1u /* keep every decoded PVS in memory: see urbanpvs_pvs_span */

/* locate() result for points outside every cell; absent neighbour. */
#define URBANPVS_NO_CELL 0xFFFFFFFFu

typedef struct urbanpvs_file urbanpvs_file;

/* Static English description of a status (never NULL). */
const char* urbanpvs_status_message(urbanpvs_status status);

/* Opens the file held in data[0, size) without copying it (see Ownership above). On success
 * *out is a new handle; on failure *out is NULL. */
urbanpvs_status urbanpvs_open_memory(const void* data, size_t size, urbanpvs_file** out);

/* Reads the file at `path` (NUL-terminated) and opens it. */
urbanpvs_status urbanpvs_open_file(const char* path, urbanpvs_file** out);

/* As urbanpvs_open_file, with URBANPVS_OPEN_* flags (0 is urbanpvs_open_file). Unknown flags:
 * URBANPVS_INVALID_ARGUMENT. */
urbanpvs_status urbanpvs_open_file_flags(const char* path, uint32_t flags, urbanpvs_file** out);

/* Releases a handle; NULL is allowed. */
void urbanpvs_close(urbanpvs_file* file);

/* Counts (0 for NULL). */
uint32_t urbanpvs_object_count(const urbanpvs_file* file);
uint32_t urbanpvs_cell_count(const urbanpvs_file* file);

/* The cell containing the local point (x, y, z), or URBANPVS_NO_CELL (see PvsFile::locate:
 * z must be inside the cell's z range; ties go to the lowest cell index). */
uint32_t urbanpvs_locate(const urbanpvs_file* file, double x, double y, double z);

/* urbanpvs_locate for a point that moves (see PvsFile::locate_from): `hint` is the cell it was
 * in; that cell when its prism contains the point, else a neighbour's that does, else
 * urbanpvs_locate. URBANPVS_NO_CELL as the hint: urbanpvs_locate. */
uint32_t urbanpvs_locate_from(const urbanpvs_file* file, uint32_t hint, double x, double y,
                              double z);

/* Input coordinates (the input CRS, or ENU for geographic inputs) -> local: subtracts the
 * stored origin. xyz[3] is read and overwritten. */
urbanpvs_status urbanpvs_input_to_local(const urbanpvs_file* file, double xyz[3]);

/* WGS84 latitude, longitude (degrees), ellipsoidal height (m) -> local frame, for files whose
 * input was geographic (URBANPVS_NOT_GEOGRAPHIC otherwise). */
urbanpvs_status urbanpvs_geodetic_to_local(const urbanpvs_file* file, double lat_deg,
                                           double lon_deg, double h_m, double local_xyz[3]);

/* Number of objects visible from `cell` (0 when out of range). */
uint32_t urbanpvs_pvs_size(const urbanpvs_file* file, uint32_t cell);

/* Number of uint32_t slots urbanpvs_pvs needs in its buffer. */
size_t urbanpvs_decode_buffer_size(const urbanpvs_file* file);

/* Writes the ascending object indices visible from `cell` to buffer[0, *count). `capacity`
 * (in elements) must be >= urbanpvs_decode_buffer_size(). No allocation. */
urbanpvs_status urbanpvs_pvs(const urbanpvs_file* file, uint32_t cell, uint32_t* buffer,
                             size_t capacity, size_t* count);

/* 1 when `object` is visible from `cell`, 0 otherwise (also for indices out of range). */
int urbanpvs_is_visible(const urbanpvs_file* file, uint32_t cell, uint32_t object);

/* The PVS of `cell` in place (ascending, valid until urbanpvs_close), for a file opened with
 * URBANPVS_OPEN_EXPAND_PVS: O(1), no copy. URBANPVS_NOT_EXPANDED otherwise. */
urbanpvs_status urbanpvs_pvs_span(const urbanpvs_file* file, uint32_t cell, const uint32_t** data,
                                  size_t* count);

/* Source id of an object (pointer into the file, not NUL-terminated) and its bounding box
 * (min x, min y, min z, max x, max y, max z; local frame). Either output may be NULL. */
urbanpvs_status urbanpvs_object(const urbanpvs_file* file, uint32_t object, const char** id,
                                size_t* id_size, double bbox[6]);

/* The user's value for an object (from the attribute or tag named when baking; pointer into the
 * file, UTF-8, not NUL-terminated): size 0 when it has none or the file has no payloads. */
urbanpvs_status urbanpvs_object_payload(const urbanpvs_file* file, uint32_t object,
                                        const char** payload, size_t* size);

/* The attribute or tag the payloads came from (size 0 when the file has none). */
void urbanpvs_payload_key(const urbanpvs_file* file, const char** key, size_t* size);

/* Triangle (x0, y0, x1, y1, x2, y2; local frame), z range (min, max) and neighbours of a cell
 * (neighbour i across the edge from vertex i to vertex i+1, or URBANPVS_NO_CELL). Any output
 * may be NULL. */
urbanpvs_status urbanpvs_cell(const urbanpvs_file* file, uint32_t cell, double triangle[6],
                              double z_range[2], uint32_t neighbours[3]);

/*
 * For streaming engines: a decoder owns the storage of set operations over PVSs, allocated on
 * its first use, so that later calls allocate nothing. One decoder per thread; it must be
 * destroyed before its file is closed. Results point into the decoder and stay valid until
 * its next call.
 */
typedef struct urbanpvs_decoder urbanpvs_decoder;

/* A decoder for `file` that keeps the list of the last cell it decoded; *out is NULL on
 * failure. */
urbanpvs_status urbanpvs_decoder_create(const urbanpvs_file* file, urbanpvs_decoder** out);
/* A decoder that keeps the lists of the last `cached_cells` cells it decoded (0 counts as 1):
 * one per agent when one decoder serves a crowd. It holds about cached_cells x
 * urbanpvs_decode_buffer_size() x 4 bytes; URBANPVS_OUT_OF_MEMORY when they cannot be had. */
urbanpvs_status urbanpvs_decoder_create_cached(const urbanpvs_file* file, size_t cached_cells,
                                               urbanpvs_decoder** out);
void urbanpvs_decoder_destroy(urbanpvs_decoder* decoder);

/* The PVS of `cell` (ascending), from the decoder's cache when it holds the cell: no copy on a
 * file opened with URBANPVS_OPEN_EXPAND_PVS. */
urbanpvs_status urbanpvs_decoder_pvs(urbanpvs_decoder* decoder, uint32_t cell,
                                     const uint32_t** objects, size_t* count);

/* The objects visible from any of cells[0, n) (ascending, each once): what to prefetch around
 * the camera or along a planned route. n == 0 gives an empty set. */
urbanpvs_status urbanpvs_pvs_union(urbanpvs_decoder* decoder, const uint32_t* cells, size_t n,
                                   const uint32_t** objects, size_t* count);

/* The camera crosses from cell `from` to cell `to`: `entered` lists the objects visible from
 * `to` but not from `from` (what to load), `left` those visible from `from` but not from `to`
 * (what may be unloaded); both ascending. */
urbanpvs_status urbanpvs_pvs_delta(urbanpvs_decoder* decoder, uint32_t from, uint32_t to,
                                   const uint32_t** entered, size_t* entered_count,
                                   const uint32_t** left, size_t* left_count);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* URBANPVS_URBANPVS_H */
