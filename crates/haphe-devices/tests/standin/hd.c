/* A stand-in for OpenHaptics' libHD.so, for haphe's tests: the HD API functions haphe
 * calls, with the headers' C signatures and constants, over simulated mechanisms (up to
 * STANDIN_DEVICES, each with its own state, configured under the names "Left", "Right",
 * "Third" and "Fourth"; the default device is the first) whose end points follow scripted
 * trajectories (millimetres, the HD frame; one sample per frame), recording every force
 * written, with a scheduler thread that runs the asynchronous callbacks every period.
 * As in the HD API, the calls that get and set values act on the current device (the one
 * last initialised, made current or whose frame was begun). Test-only symbols (standin_*)
 * script them: those without _of act on device 0. */
#include <pthread.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "env.h"

typedef unsigned int HHD;
typedef unsigned int HDenum;
typedef unsigned int HDerror;
typedef unsigned int HDCallbackCode;
typedef unsigned long HDSchedulerHandle;
typedef HDCallbackCode (*HDSchedulerCallback)(void *);
typedef struct { HDerror errorCode; int internalErrorCode; HHD hHD; } HDErrorInfo;

#define HD_INVALID_HANDLE 0xFFFFFFFFu
#define HD_DEVICE_FAULT 0x0101
#define HD_DEVICE_ALREADY_INITIATED 0x0102
#define HD_COMM_ERROR 0x0302
#define HD_ILLEGAL_BEGIN 0x0400
#define HD_CURRENT_BUTTONS 0x2000
#define HD_CURRENT_POSITION 0x2050
#define HD_CURRENT_VELOCITY 0x2051
#define HD_DEVICE_MODEL_TYPE 0x2501
#define HD_USABLE_WORKSPACE_DIMENSIONS 0x2551
#define HD_UPDATE_RATE 0x2600
#define HD_NOMINAL_MAX_STIFFNESS 0x2602
#define HD_NOMINAL_MAX_CONTINUOUS_FORCE 0x2604
#define HD_CURRENT_FORCE 0x2700
#define HD_FORCE_OUTPUT 0x4000
#define HD_CALLBACK_DONE 0

#define STANDIN_MAX 400000
#define STANDIN_DEVICES 4

struct standin_device {
  double samples[STANDIN_MAX][6]; /* position mm, velocity mm/s, HD frame */
  int n_samples;
  int current;
  double forces[STANDIN_MAX][3];
  int n_forces;
  int fail_from;
  int frames;
  int in_frame;
  int initialised;
  int force_output;
};

static const char *names[STANDIN_DEVICES] = {"Left", "Right", "Third", "Fourth"};
static struct standin_device dev[STANDIN_DEVICES];
static int present = 1;
static int current_device = -1;
static HDerror pending = 0;
static long period_ns = 1000000;

static HDSchedulerCallback callback = NULL;
static void *callback_data = NULL;
static volatile int running = 0;
static pthread_t scheduler;
static int scheduler_started = 0;
/* Whether the state was set up: by standin_reset, or with one device at the first call
 * (a process that runs haphe scripts it through the environment only); the number of
 * devices connected is then HAPHE_STANDIN_DEVICES's, 1 by default. */
static int ready = 0;
void standin_reset(int devices_present);
static void init(void) {
  const char *n = getenv("HAPHE_STANDIN_DEVICES");
  if (!ready) standin_reset(1);
  /* Read at every call: a process may load the stand-in before it sets the variable. */
  if (n) present = atoi(n) < STANDIN_DEVICES ? atoi(n) : STANDIN_DEVICES;
}

void standin_reset(int devices_present) {
  for (int i = 0; i < STANDIN_DEVICES; i++) {
    struct standin_device *d = &dev[i];
    d->n_samples = 0; d->current = -1; d->n_forces = 0; d->fail_from = -1; d->frames = 0;
    d->in_frame = 0; d->initialised = 0; d->force_output = 0;
  }
  present = devices_present < STANDIN_DEVICES ? devices_present : STANDIN_DEVICES;
  current_device = -1; pending = 0; period_ns = 1000000;
  callback = NULL; callback_data = NULL; n_button_masks = 0; ready = 1;
}
static struct standin_device *of(int i) { init(); return i >= 0 && i < STANDIN_DEVICES ? &dev[i] : NULL; }
int standin_set_path_of(int i, const double *pv, int n) {
  struct standin_device *d = of(i);
  if (!d) return 0;
  if (n > STANDIN_MAX) n = STANDIN_MAX;
  memcpy(d->samples, pv, sizeof(double) * 6 * (size_t)n);
  d->n_samples = n;
  return n;
}
int standin_set_path(const double *pv, int n) { return standin_set_path_of(0, pv, n); }
void standin_fail_from_of(int i, int frame) { if (of(i)) dev[i].fail_from = frame; }
void standin_fail_from(int frame) { standin_fail_from_of(0, frame); }
void standin_set_period_ns(long ns) { init(); period_ns = ns; }
int standin_forces_of(int i, double *out, int max) {
  struct standin_device *d = of(i);
  if (!d) return 0;
  int n = d->n_forces < max ? d->n_forces : max;
  memcpy(out, d->forces, sizeof(double) * 3 * (size_t)n);
  return d->n_forces;
}
int standin_forces(double *out, int max) { return standin_forces_of(0, out, max); }
int standin_force_output_of(int i) { return of(i) ? dev[i].force_output : 0; }
int standin_force_output(void) { return standin_force_output_of(0); }

static void error(HDerror e) { if (!pending) pending = e; }
/* The device of handle h (handles are the index + 1), if it is initialised. */
static struct standin_device *handle(HHD h) {
  init();
  struct standin_device *d = h >= 1 && h <= STANDIN_DEVICES ? &dev[h - 1] : NULL;
  return d && d->initialised ? d : NULL;
}
static struct standin_device *current(void) {
  struct standin_device *d = of(current_device);
  return d && d->initialised ? d : NULL;
}

HHD hdInitDevice(const char *name) {
  int i = 0;
  init();
  if (name) {
    for (i = 0; i < STANDIN_DEVICES && strcmp(names[i], name) != 0; i++) {}
  }
  if (i >= present) { error(HD_DEVICE_FAULT); return HD_INVALID_HANDLE; }
  struct standin_device *d = &dev[i];
  if (d->initialised) { error(HD_DEVICE_ALREADY_INITIATED); return HD_INVALID_HANDLE; }
  d->initialised = 1;
  current_device = i;
  int n = standin_env_path(i, d->samples, STANDIN_MAX);
  if (n >= 0) { d->n_samples = n; d->current = -1; d->n_forces = 0; d->frames = 0; }
  int fail = standin_env_int("HAPHE_STANDIN_FAIL_FROM", i);
  if (fail >= 0) d->fail_from = fail;
  return (HHD)(i + 1);
}
void hdDisableDevice(HHD h) {
  struct standin_device *d = handle(h);
  if (!d) { error(HD_DEVICE_FAULT); return; }
  standin_env_report((int)h - 1, d->forces, d->n_forces, STANDIN_MAX, d->force_output);
  d->initialised = 0;
}
void hdMakeCurrentDevice(HHD h) {
  if (!handle(h)) { error(HD_DEVICE_FAULT); return; }
  current_device = (int)h - 1;
}
void hdBeginFrame(HHD h) {
  struct standin_device *d = handle(h);
  if (!d) { error(HD_DEVICE_FAULT); return; }
  current_device = (int)h - 1;
  if (d->in_frame) { error(HD_ILLEGAL_BEGIN); return; }
  d->in_frame = 1;
  if (d->fail_from >= 0 && d->frames >= d->fail_from) { error(HD_COMM_ERROR); return; }
  d->frames++;
  if (d->current + 1 < d->n_samples) d->current++;
}
void hdEndFrame(HHD h) { struct standin_device *d = handle(h); if (d) d->in_frame = 0; }
void hdEnable(HDenum cap) { struct standin_device *d = current(); if (d && cap == HD_FORCE_OUTPUT) d->force_output = 1; }
void hdDisable(HDenum cap) { struct standin_device *d = current(); if (d && cap == HD_FORCE_OUTPUT) d->force_output = 0; }
void hdGetDoublev(HDenum what, double *v) {
  static const double workspace[6] = {-80.0, -60.0, -35.0, 80.0, 60.0, 35.0};
  struct standin_device *d = current();
  switch (what) {
  case HD_CURRENT_POSITION:
  case HD_CURRENT_VELOCITY: {
    int o = what == HD_CURRENT_POSITION ? 0 : 3;
    if (!d || d->current < 0) { v[0] = v[1] = v[2] = 0.0; if (o == 0) v[1] = 1000.0; return; }
    v[0] = d->samples[d->current][o]; v[1] = d->samples[d->current][o + 1]; v[2] = d->samples[d->current][o + 2];
    return;
  }
  case HD_USABLE_WORKSPACE_DIMENSIONS: memcpy(v, workspace, sizeof workspace); return;
  case HD_NOMINAL_MAX_CONTINUOUS_FORCE: v[0] = 3.3; return;
  case HD_NOMINAL_MAX_STIFFNESS: v[0] = 2.0; return;
  default: v[0] = 0.0; return;
  }
}
void hdGetIntegerv(HDenum what, int *v) {
  struct standin_device *d = current();
  if (what == HD_UPDATE_RATE) *v = 1000;
  /* The scripted buttons are device 0's. */
  else if (what == HD_CURRENT_BUTTONS) *v = d == &dev[0] ? (int)standin_buttons_at(d->current) : 0;
  else *v = 0;
}
void hdSetDoublev(HDenum what, const double *v) {
  struct standin_device *d = current();
  if (what != HD_CURRENT_FORCE || !d) return;
  if (d->n_forces < STANDIN_MAX) {
    d->forces[d->n_forces][0] = v[0]; d->forces[d->n_forces][1] = v[1]; d->forces[d->n_forces][2] = v[2];
    d->n_forces++;
  }
}
const char *hdGetString(HDenum what) {
  static const char *models[STANDIN_DEVICES] = {"stand-in Touch", "stand-in Touch X", "stand-in Touch", "stand-in Touch"};
  return what == HD_DEVICE_MODEL_TYPE && current() ? models[current_device] : "";
}
HDErrorInfo hdGetError(void) {
  HDErrorInfo e = {pending, 0, (HHD)(current_device + 1)};
  pending = 0;
  return e;
}
const char *hdGetErrorString(HDerror e) {
  return e == HD_COMM_ERROR ? "Communication error" : e == HD_ILLEGAL_BEGIN ? "Illegal begin"
       : e == HD_DEVICE_FAULT ? "Device fault" : e == HD_DEVICE_ALREADY_INITIATED ? "Device already initiated"
       : "Unknown error";
}

static void *scheduler_main(void *unused) {
  (void)unused;
  struct timespec next;
  clock_gettime(CLOCK_MONOTONIC, &next);
  while (running) {
    if (callback && callback(callback_data) == HD_CALLBACK_DONE) callback = NULL;
    if (period_ns > 0) {
      next.tv_nsec += period_ns;
      while (next.tv_nsec >= 1000000000L) { next.tv_nsec -= 1000000000L; next.tv_sec++; }
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL);
    } else {
      sched_yield();
    }
  }
  return NULL;
}
HDSchedulerHandle hdScheduleAsynchronous(HDSchedulerCallback cb, void *data, unsigned short priority) {
  (void)priority;
  callback_data = data;
  callback = cb;
  return 1;
}
void hdUnschedule(HDSchedulerHandle h) { (void)h; callback = NULL; }
void hdStartScheduler(void) {
  if (scheduler_started) return;
  running = 1;
  if (pthread_create(&scheduler, NULL, scheduler_main, NULL) != 0) { running = 0; error(HD_COMM_ERROR); return; }
  scheduler_started = 1;
}
void hdStopScheduler(void) {
  if (!scheduler_started) return;
  running = 0;
  pthread_join(scheduler, NULL);
  scheduler_started = 0;
}
