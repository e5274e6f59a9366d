/* C-callable functions for c_api_test.c, implemented in C++ (c_api_test_support.cpp) with the
 * table writer of table_writer.h. Valid C99. */
#ifndef WRC_TESTS_RUNTIME_C_API_TEST_SUPPORT_H_
#define WRC_TESTS_RUNTIME_C_API_TEST_SUPPORT_H_

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes the C test's table to a fresh scratch path, copied into path (capacity bytes):
 * axes y = -2, -1, 0, 1, 2 and spin = -0.01, 0, 0.01; outputs
 *   fx = 1 + 2·y + 300·spin + 50·y·spin,  fy = y².
 * Returns 0, or -1 (with a message on stderr). */
int wrc_test_write_c_table(char* path, size_t capacity);

/* Deletes the file (ignores errors). */
void wrc_test_remove(const char* path);

#ifdef __cplusplus
}
#endif

#endif /* WRC_TESTS_RUNTIME_C_API_TEST_SUPPORT_H_ */
