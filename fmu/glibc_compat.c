/* Lets the linux64 FMU library load on glibc 2.17 (RHEL/CentOS 7, Ubuntu 14.04 and later)
 * although it is built on a newer glibc (docs/fmu.md "Platforms").
 *
 * Linking against a new glibc binds each libc function to its newest symbol version: the
 * statically linked libstdc++ and the project's code then ask for pthread_create@GLIBC_2.34,
 * exp@GLIBC_2.29, stat@GLIBC_2.33 and so on, and an older glibc refuses to load the library.
 * fmu/CMakeLists.txt links with -Wl,--wrap=NAME for each of those, which sends every call of
 * NAME to __wrap_NAME below; each wrapper calls the oldest version of the function (bound with
 * .symver), which newer glibc keeps for old binaries, or, where the function is newer than
 * 2.17, does the same with what 2.17 has. tests/fmu reads the library's symbol versions and
 * fails if any is newer than GLIBC_2.17.
 *
 * Only for x86_64 glibc builds of the FMU; nothing else links it. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stddef.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#define OLD(name, version) __asm__(".symver " #name "_old, " #name "@" version)

/* memcpy@GLIBC_2.14 is the memcpy that may not overlap; 2.2.5's is memmove, a superset. */
void* memcpy_old(void*, const void*, size_t);
OLD(memcpy, "GLIBC_2.2.5");
void* __wrap_memcpy(void* d, const void* s, size_t n) { return memcpy_old(d, s, n); }

/* libm 2.29 gave exp, log and pow new versions (faster, same results to the ulp the tests
 * allow); the old ones stay. */
double exp_old(double);
double log_old(double);
double pow_old(double, double);
OLD(exp, "GLIBC_2.2.5");
OLD(log, "GLIBC_2.2.5");
OLD(pow, "GLIBC_2.2.5");
double __wrap_exp(double x) { return exp_old(x); }
double __wrap_log(double x) { return log_old(x); }
double __wrap_pow(double x, double y) { return pow_old(x, y); }

/* glibc 2.34 moved the pthread functions from libpthread into libc with new versions; the
 * 2.2.5 versions are what libpthread.so.0 (linked as well) provides on an older glibc. */
int pthread_create_old(pthread_t*, const pthread_attr_t*, void* (*)(void*), void*);
int pthread_detach_old(pthread_t);
int pthread_join_old(pthread_t, void**);
int pthread_key_create_old(pthread_key_t*, void (*)(void*));
int __pthread_key_create_old(pthread_key_t*, void (*)(void*));
int pthread_key_delete_old(pthread_key_t);
void* pthread_getspecific_old(pthread_key_t);
int pthread_setspecific_old(pthread_key_t, const void*);
int pthread_once_old(pthread_once_t*, void (*)(void));
int pthread_cond_timedwait_old(pthread_cond_t*, pthread_mutex_t*, const struct timespec*);
OLD(pthread_create, "GLIBC_2.2.5");
OLD(pthread_detach, "GLIBC_2.2.5");
OLD(pthread_join, "GLIBC_2.2.5");
OLD(pthread_key_create, "GLIBC_2.2.5");
OLD(__pthread_key_create, "GLIBC_2.2.5");
OLD(pthread_key_delete, "GLIBC_2.2.5");
OLD(pthread_getspecific, "GLIBC_2.2.5");
OLD(pthread_setspecific, "GLIBC_2.2.5");
OLD(pthread_once, "GLIBC_2.2.5");
OLD(pthread_cond_timedwait, "GLIBC_2.3.2");
int __wrap_pthread_create(pthread_t* t, const pthread_attr_t* a, void* (*f)(void*), void* arg) {
  return pthread_create_old(t, a, f, arg);
}
int __wrap_pthread_detach(pthread_t t) { return pthread_detach_old(t); }
int __wrap_pthread_join(pthread_t t, void** r) { return pthread_join_old(t, r); }
int __wrap_pthread_key_create(pthread_key_t* k, void (*d)(void*)) { return pthread_key_create_old(k, d); }
int __wrap___pthread_key_create(pthread_key_t* k, void (*d)(void*)) { return __pthread_key_create_old(k, d); }
int __wrap_pthread_key_delete(pthread_key_t k) { return pthread_key_delete_old(k); }
void* __wrap_pthread_getspecific(pthread_key_t k) { return pthread_getspecific_old(k); }
int __wrap_pthread_setspecific(pthread_key_t k, const void* v) { return pthread_setspecific_old(k, v); }
int __wrap_pthread_once(pthread_once_t* o, void (*f)(void)) { return pthread_once_old(o, f); }

/* pthread_cond_clockwait (glibc 2.30) is what std::condition_variable uses to wait on the
 * steady clock. 2.17 has only pthread_cond_timedwait on the condition variable's clock, the
 * real-time clock for the default one std::condition_variable makes: the deadline is moved
 * to that clock. A step of the wall clock during the wait makes the wait end early or late;
 * the thermal worker's waits are short polls that re-check their condition, so that costs at
 * most one poll. */
int __wrap_pthread_cond_clockwait(pthread_cond_t* cond, pthread_mutex_t* mutex, clockid_t clock,
                                  const struct timespec* abstime) {
  if (clock == CLOCK_REALTIME) return pthread_cond_timedwait_old(cond, mutex, abstime);
  if (clock != CLOCK_MONOTONIC) return EINVAL;
  struct timespec now_clock, now_real, deadline;
  clock_gettime(clock, &now_clock);
  clock_gettime(CLOCK_REALTIME, &now_real);
  long long ns =
      (long long)(abstime->tv_sec - now_clock.tv_sec) * 1000000000LL + (abstime->tv_nsec - now_clock.tv_nsec);
  if (ns < 0) ns = 0;
  ns += now_real.tv_nsec;
  deadline.tv_sec = now_real.tv_sec + (time_t)(ns / 1000000000LL);
  deadline.tv_nsec = (long)(ns % 1000000000LL);
  return pthread_cond_timedwait_old(cond, mutex, &deadline);
}

/* stat, lstat and fstat64 became functions in glibc 2.33; before, they were inline calls of
 * __xstat, __lxstat and __fxstat64 with the structure version 1 (_STAT_VER_LINUX, x86_64). */
int __xstat_old(int, const char*, struct stat*);
int __lxstat_old(int, const char*, struct stat*);
int __fxstat64_old(int, int, struct stat64*);
OLD(__xstat, "GLIBC_2.2.5");
OLD(__lxstat, "GLIBC_2.2.5");
OLD(__fxstat64, "GLIBC_2.2.5");
int __wrap_stat(const char* path, struct stat* buf) { return __xstat_old(1, path, buf); }
int __wrap_lstat(const char* path, struct stat* buf) { return __lxstat_old(1, path, buf); }
int __wrap_fstat64(int fd, struct stat64* buf) { return __fxstat64_old(1, fd, buf); }

/* getentropy (2.25) and arc4random (2.36) are what libstdc++'s std::random_device reads; it
 * is linked in with the string code exceptions use, though the FMU never makes one. Same
 * contract from /dev/urandom, which 2.17's kernels (3.10) have and getrandom() not always. */
int __wrap_getentropy(void* buffer, size_t length) {
  if (length > 256) {
    errno = EIO;
    return -1;
  }
  const int fd = open("/dev/urandom", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return -1;
  size_t got = 0;
  while (got < length) {
    const ssize_t r = read(fd, (char*)buffer + got, length - got);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) {
      close(fd);
      errno = EIO;
      return -1;
    }
    got += (size_t)r;
  }
  close(fd);
  return 0;
}
unsigned int __wrap_arc4random(void) {
  unsigned int value = 0;
  if (__wrap_getentropy(&value, sizeof value) != 0) {
    /* arc4random cannot fail; without /dev/urandom, the clock is the only entropy left. */
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    value = (unsigned int)now.tv_nsec ^ (unsigned int)now.tv_sec * 2654435761u;
  }
  return value;
}

/* glibc 2.32's flag that lets libstdc++ skip atomic reference counts in a single-threaded
 * process. Defined here (hidden, so the library's own references bind to it) as 0: "maybe
 * threaded", always the atomic path, which is what an older glibc means too. */
__attribute__((visibility("hidden"))) char __libc_single_threaded = 0;

/* glibc 2.18 added __cxa_thread_atexit_impl, which libstdc++ calls to run the destructors of
 * thread_local objects when their thread ends (the network FMU has some: the fixed-step
 * stepper's workspace, dynamics/simulation.cpp). Here the same with what 2.17 has, as
 * libstdc++ itself does on a glibc without it: a list per thread, run newest first by a
 * pthread key's destructor. Like that fallback it does not keep the library loaded until the
 * destructors ran (a master that unloads the FMU while a thread that stepped it still runs
 * must not let that thread end afterwards), and the main thread's list is left to the
 * process's exit. */
struct thread_dtor {
  void (*dtor)(void*);
  void* obj;
  struct thread_dtor* next;
};
static pthread_key_t thread_dtor_key;
static pthread_once_t thread_dtor_once = PTHREAD_ONCE_INIT;
static void run_thread_dtors(void* p) {
  struct thread_dtor* d = p;
  while (d) {
    struct thread_dtor* next = d->next;
    d->dtor(d->obj);
    free(d);
    d = next;
  }
}
static void make_thread_dtor_key(void) { pthread_key_create_old(&thread_dtor_key, run_thread_dtors); }
int __wrap___cxa_thread_atexit_impl(void (*dtor)(void*), void* obj, void* dso_handle) {
  (void)dso_handle;
  pthread_once_old(&thread_dtor_once, make_thread_dtor_key);
  struct thread_dtor* d = malloc(sizeof *d);
  if (!d) return -1;
  d->dtor = dtor;
  d->obj = obj;
  d->next = pthread_getspecific_old(thread_dtor_key);
  pthread_setspecific_old(thread_dtor_key, d);
  return 0;
}
