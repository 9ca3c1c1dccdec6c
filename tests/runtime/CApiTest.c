/* SPDX-License-Identifier: MIT */
/* The C API from a translation unit compiled as C99: open a golden file (v1_0.pvs, v2_1.pvs
 * with payloads or v2_2.pvs with payloads and the coded PVS), locate, decode. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "urbanpvs/urbanpvs.h"

static int failures = 0;

#define CHECK(cond)                                                      \
  do {                                                                   \
    if (!(cond)) {                                                       \
      fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                        \
    }                                                                    \
  } while (0)

int main(int argc, char** argv) {
  urbanpvs_file* file = NULL;
  uint32_t* buffer;
  size_t count = 0, id_size = 0;
  const char *id = NULL, *payload = NULL, *key = NULL;
  size_t payload_size = 0, key_size = 0;
  int with_payloads;
  double bbox[6], triangle[6], z[2], xyz[3] = {85002.0, 446002.0, 0.25}, local[3];
  uint32_t neighbours[3], cell, o;
  urbanpvs_decoder* decoder = NULL;
  const uint32_t *objects = NULL, *entered = NULL, *left = NULL;
  size_t n_entered = 0, n_left = 0, k;
  const uint32_t cells[3] = {1, 2, 4}, bad_cells[2] = {1, 6};
  if (argc != 2) {
    fprintf(stderr, "usage: %s GOLDEN.pvs\n", argv[0]);
    return 2;
  }
  CHECK(urbanpvs_open_file("/nonexistent.pvs", &file) == URBANPVS_IO_ERROR && file == NULL);
  CHECK(urbanpvs_open_memory("not a pvs file", 14, &file) == URBANPVS_BAD_MAGIC);
  CHECK(strcmp(urbanpvs_status_message(URBANPVS_BAD_MAGIC), "not a .pvs file (bad magic)") == 0);
  CHECK(urbanpvs_open_file(argv[1], &file) == URBANPVS_OK && file != NULL);
  if (file == NULL) return 1;
  CHECK(urbanpvs_object_count(file) == 120);
  CHECK(urbanpvs_cell_count(file) == 6);

  CHECK(urbanpvs_input_to_local(file, xyz) == URBANPVS_OK);
  CHECK(xyz[0] == 2.0 && xyz[1] == 2.0 && xyz[2] == 1.75);
  CHECK(urbanpvs_locate(file, xyz[0], xyz[1], xyz[2]) == 0);
  cell = urbanpvs_locate(file, 12.0, 2.0, 1.75);
  CHECK(cell == 2);
  CHECK(urbanpvs_locate(file, 100.0, 2.0, 1.75) == URBANPVS_NO_CELL);
  /* From a hint: the hint when it holds the point, else what holds it, else nothing. */
  CHECK(urbanpvs_locate_from(file, 2, 12.0, 2.0, 1.75) == 2);
  CHECK(urbanpvs_locate_from(file, 0, 12.0, 2.0, 1.75) == 2);
  CHECK(urbanpvs_locate_from(file, URBANPVS_NO_CELL, 12.0, 2.0, 1.75) == 2);
  CHECK(urbanpvs_locate_from(file, 2, 100.0, 2.0, 1.75) == URBANPVS_NO_CELL);
  CHECK(urbanpvs_locate_from(NULL, 2, 12.0, 2.0, 1.75) == URBANPVS_NO_CELL);
  CHECK(urbanpvs_geodetic_to_local(file, 52.0, 4.0, 0.0, local) == URBANPVS_NOT_GEOGRAPHIC);

  buffer = (uint32_t*)malloc(urbanpvs_decode_buffer_size(file) * sizeof *buffer);
  CHECK(urbanpvs_pvs(file, cell, buffer, 1, &count) == URBANPVS_BUFFER_TOO_SMALL);
  CHECK(urbanpvs_pvs(file, cell, buffer, urbanpvs_decode_buffer_size(file), &count) == URBANPVS_OK);
  CHECK(count == 10 && urbanpvs_pvs_size(file, cell) == 10);
  CHECK(buffer[1] == 3 && buffer[9] == 111);
  CHECK(urbanpvs_pvs(file, 6, buffer, urbanpvs_decode_buffer_size(file), &count) ==
        URBANPVS_OUT_OF_RANGE);
  free(buffer);
  CHECK(urbanpvs_is_visible(file, 2, 3) == 1);
  CHECK(urbanpvs_is_visible(file, 2, 39) == 0);
  CHECK(urbanpvs_is_visible(file, 99, 3) == 0);

  CHECK(urbanpvs_object(file, 3, &id, &id_size, bbox) == URBANPVS_OK);
  CHECK(id_size == 18 && strncmp(id, "NL.IMBAG.Pand.1003", id_size) == 0);
  CHECK(bbox[0] == 20.0 && bbox[5] == 9.0);
  CHECK(urbanpvs_object(file, 120, &id, &id_size, bbox) == URBANPVS_OUT_OF_RANGE);
  /* Payloads: v2_1.pvs carries "tile" values (every third object none), v1_0.pvs none. */
  urbanpvs_payload_key(file, &key, &key_size);
  with_payloads = key_size == 4 && strncmp(key, "tile", 4) == 0;
  CHECK(with_payloads || key_size == 0);
  CHECK(urbanpvs_object_payload(file, 3, &payload, &payload_size) == URBANPVS_OK);
  CHECK(with_payloads ? payload_size == 13 && strncmp(payload, "tiles/0/3.glb", 13) == 0
                      : payload_size == 0);
  CHECK(urbanpvs_object_payload(file, 2, &payload, &payload_size) == URBANPVS_OK);
  CHECK(payload_size == 0);
  CHECK(urbanpvs_object_payload(file, 120, &payload, &payload_size) == URBANPVS_OUT_OF_RANGE);
  CHECK(urbanpvs_object_payload(file, 3, NULL, &payload_size) == URBANPVS_INVALID_ARGUMENT);
  urbanpvs_payload_key(NULL, &key, &key_size);
  CHECK(key_size == 0);
  CHECK(urbanpvs_cell(file, 2, triangle, z, neighbours) == URBANPVS_OK);
  CHECK(triangle[0] == 10.0 && triangle[2] == 20.0 && z[1] == 3.0);
  CHECK(neighbours[0] == URBANPVS_NO_CELL && neighbours[1] == 3 && neighbours[2] == 1);
  CHECK(urbanpvs_cell(file, 2, NULL, NULL, NULL) == URBANPVS_OK);
  CHECK(urbanpvs_cell(NULL, 2, NULL, NULL, NULL) == URBANPVS_INVALID_ARGUMENT);

  /* Union and delta, checked object by object against urbanpvs_is_visible. */
  CHECK(urbanpvs_decoder_create(NULL, &decoder) == URBANPVS_INVALID_ARGUMENT && decoder == NULL);
  CHECK(urbanpvs_decoder_create(file, &decoder) == URBANPVS_OK && decoder != NULL);
  CHECK(urbanpvs_pvs_union(decoder, cells, 3, &objects, &count) == URBANPVS_OK);
  for (o = 0, k = 0; o < 120; ++o)
    if (urbanpvs_is_visible(file, 1, o) || urbanpvs_is_visible(file, 2, o) ||
        urbanpvs_is_visible(file, 4, o)) {
      CHECK(k < count && objects[k] == o);
      ++k;
    }
  CHECK(k == count && count > urbanpvs_pvs_size(file, 2));
  CHECK(urbanpvs_pvs_union(decoder, bad_cells, 2, &objects, &count) == URBANPVS_OUT_OF_RANGE);
  CHECK(count == 0);
  CHECK(urbanpvs_pvs_delta(decoder, 2, 3, &entered, &n_entered, &left, &n_left) == URBANPVS_OK);
  {
    size_t e = 0, l = 0;
    for (o = 0; o < 120; ++o) {
      const int before = urbanpvs_is_visible(file, 2, o), after = urbanpvs_is_visible(file, 3, o);
      if (after && !before) {
        CHECK(e < n_entered && entered[e] == o);
        ++e;
      }
      if (before && !after) {
        CHECK(l < n_left && left[l] == o);
        ++l;
      }
    }
    CHECK(e == n_entered && l == n_left && e + l > 0);
  }
  CHECK(urbanpvs_pvs_delta(decoder, 2, 6, &entered, &n_entered, &left, &n_left) ==
        URBANPVS_OUT_OF_RANGE);
  CHECK(n_entered == 0 && n_left == 0);
  CHECK(urbanpvs_pvs_delta(decoder, 2, 3, NULL, &n_entered, &left, &n_left) ==
        URBANPVS_INVALID_ARGUMENT);
  urbanpvs_decoder_destroy(decoder);
  urbanpvs_decoder_destroy(NULL);

  /* A decoder that caches cells: each cell's list, object by object, twice (the second time
   * from its cache); a cache that cannot be had is refused. */
  CHECK(urbanpvs_decoder_create_cached(file, 8, &decoder) == URBANPVS_OK && decoder != NULL);
  {
    uint32_t c;
    int round;
    for (round = 0; round < 2; ++round)
      for (c = 0; c < urbanpvs_cell_count(file); ++c) {
        CHECK(urbanpvs_decoder_pvs(decoder, c, &objects, &count) == URBANPVS_OK);
        CHECK(count == urbanpvs_pvs_size(file, c));
        for (o = 0, k = 0; o < 120; ++o)
          if (urbanpvs_is_visible(file, c, o)) {
            CHECK(k < count && objects[k] == o);
            ++k;
          }
        CHECK(k == count);
      }
    CHECK(urbanpvs_decoder_pvs(decoder, c, &objects, &count) == URBANPVS_OUT_OF_RANGE);
    CHECK(count == 0);
    CHECK(urbanpvs_decoder_pvs(decoder, 0, NULL, &count) == URBANPVS_INVALID_ARGUMENT);
  }
  urbanpvs_decoder_destroy(decoder);
  decoder = (urbanpvs_decoder*)1;
  CHECK(urbanpvs_decoder_create_cached(file, (size_t)-1, &decoder) == URBANPVS_OUT_OF_MEMORY &&
        decoder == NULL);
  urbanpvs_close(file);
  urbanpvs_close(NULL);
  if (failures == 0) printf("C API: all checks passed\n");
  return failures == 0 ? 0 : 1;
}
