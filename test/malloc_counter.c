/* SPDX-License-Identifier: MIT */
/* Counts the calls to malloc, calloc and realloc of the whole test program, the bytes they
 * ask for and the largest single request, for the allocation tests (test_allocations.f90,
 * test_adm_text.f90): defining these symbols in the executable interposes them for every
 * caller (gfortran's ALLOCATE, array temporaries, libgfortran, SUNDIALS). glibc exports the
 * real allocator as __libc_malloc & co.; elsewhere nothing is interposed and
 * rollcon_malloc_counting() says so, and the tests skip.
 * It lives beside test/main.f90, not in the suites' package (test/unit): fpm 0.12 links a C
 * source of the [[test]]'s own folder into that program alone, but one of a dev-dependency
 * into every program it builds, rollcon and rollcon-sweep included, whose malloc it then
 * replaced (suite fpm-dependency, programs-without-the-tests-allocator). */
#include <stdlib.h>

static long calls = 0;
static long long bytes = 0;
static long long largest = 0;

/* The largest single request so far (since rollcon_malloc_reset_largest). */
static void note_size(long long size)
{
    if (size > largest) largest = size;
}

#ifdef __GLIBC__
extern void *__libc_malloc(size_t size);
extern void *__libc_calloc(size_t count, size_t size);
extern void *__libc_realloc(void *pointer, size_t size);

void *malloc(size_t size)
{
    calls++;
    bytes += (long long)size;
    note_size((long long)size);
    return __libc_malloc(size);
}

void *calloc(size_t count, size_t size)
{
    calls++;
    bytes += (long long)(count * size);
    note_size((long long)(count * size));
    return __libc_calloc(count, size);
}

void *realloc(void *pointer, size_t size)
{
    calls++;
    bytes += (long long)size;
    note_size((long long)size);
    return __libc_realloc(pointer, size);
}

int rollcon_malloc_counting(void) { return 1; }
#else
int rollcon_malloc_counting(void) { return 0; }
#endif

/* Calls to the allocator since the program started. */
long rollcon_malloc_count(void) { return calls; }

/* Bytes asked of the allocator since the program started (a realloc counts its new size):
 * a list grown by concatenation asks for quadratically many (test_adm_text.f90). */
long long rollcon_malloc_bytes(void) { return bytes; }

/* The largest single request of malloc, calloc or realloc since the last reset [bytes]: a run
 * that holds no n x n array asks for none that large (test_allocations.f90). */
long long rollcon_malloc_largest(void) { return largest; }

/* Forget the largest request: the next rollcon_malloc_largest counts from here. */
void rollcon_malloc_reset_largest(void) { largest = 0; }
