/* A stand-in for OpenHaptics' libHD.so, for haphe's tests: the HD API functions haphe
 * calls, with the headers' C signatures and constants, over a simulated mechanism whose
 * end point follows a scripted trajectory (millimetres, the HD frame; one sample per
 * frame), recording every force written, with a scheduler thread that runs the
 * asynchronous callbacks every period. Test-only symbols (standin_*) script it. */
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

static double samples[STANDIN_MAX][6]; /* position mm, velocity mm/s, HD frame */
static int n_samples = 0;
static int current = -1;
static double forces[STANDIN_MAX][3];
static int n_forces = 0;
static int fail_from = -1;
static int frames = 0;
static int in_frame = 0;
static int present = 1;
static int initialised = 0;
static int force_output = 0;
static HDerror pending = 0;
static long period_ns = 1000000;

static HDSchedulerCallback callback = NULL;
static void *callback_data = NULL;
static volatile int running = 0;
static pthread_t scheduler;
static int scheduler_started = 0;

void standin_reset(int device_present) {
  n_samples = 0; current = -1; n_forces = 0; fail_from = -1; frames = 0; in_frame = 0;
  present = device_present; initialised = 0; force_output = 0; pending = 0; period_ns = 1000000;
  callback = NULL; callback_data = NULL; n_button_masks = 0;
}
int standin_set_path(const double *pv, int n) {
  if (n > STANDIN_MAX) n = STANDIN_MAX;
  memcpy(samples, pv, sizeof(double) * 6 * (size_t)n);
  n_samples = n;
  return n;
}
void standin_fail_from(int frame) { fail_from = frame; }
void standin_set_period_ns(long ns) { period_ns = ns; }
int standin_forces(double *out, int max) {
  int n = n_forces < max ? n_forces : max;
  memcpy(out, forces, sizeof(double) * 3 * (size_t)n);
  return n_forces;
}
int standin_force_output(void) { return force_output; }

static void error(HDerror e) { if (!pending) pending = e; }

HHD hdInitDevice(const char *name) {
  (void)name;
  if (!present) { error(HD_COMM_ERROR); return HD_INVALID_HANDLE; }
  initialised = 1;
  int n = standin_env_path(samples, STANDIN_MAX);
  if (n >= 0) { n_samples = n; current = -1; n_forces = 0; frames = 0; }
  return 1;
}
void hdDisableDevice(HHD h) {
  (void)h;
  standin_env_report(forces, n_forces, STANDIN_MAX, force_output);
  initialised = 0;
}
void hdMakeCurrentDevice(HHD h) { (void)h; }
void hdBeginFrame(HHD h) {
  (void)h;
  if (in_frame) { error(HD_ILLEGAL_BEGIN); return; }
  in_frame = 1;
  if (fail_from >= 0 && frames >= fail_from) { error(HD_COMM_ERROR); return; }
  frames++;
  if (current + 1 < n_samples) current++;
}
void hdEndFrame(HHD h) { (void)h; in_frame = 0; }
void hdEnable(HDenum cap) { if (cap == HD_FORCE_OUTPUT) force_output = 1; }
void hdDisable(HDenum cap) { if (cap == HD_FORCE_OUTPUT) force_output = 0; }
void hdGetDoublev(HDenum what, double *v) {
  static const double workspace[6] = {-80.0, -60.0, -35.0, 80.0, 60.0, 35.0};
  switch (what) {
  case HD_CURRENT_POSITION:
  case HD_CURRENT_VELOCITY: {
    int o = what == HD_CURRENT_POSITION ? 0 : 3;
    if (current < 0) { v[0] = v[1] = v[2] = 0.0; if (o == 0) v[1] = 1000.0; return; }
    v[0] = samples[current][o]; v[1] = samples[current][o + 1]; v[2] = samples[current][o + 2];
    return;
  }
  case HD_USABLE_WORKSPACE_DIMENSIONS: memcpy(v, workspace, sizeof workspace); return;
  case HD_NOMINAL_MAX_CONTINUOUS_FORCE: v[0] = 3.3; return;
  case HD_NOMINAL_MAX_STIFFNESS: v[0] = 2.0; return;
  default: v[0] = 0.0; return;
  }
}
void hdGetIntegerv(HDenum what, int *v) {
  if (what == HD_UPDATE_RATE) *v = 1000;
  else if (what == HD_CURRENT_BUTTONS) *v = (int)standin_buttons_at(current);
  else *v = 0;
}
void hdSetDoublev(HDenum what, const double *v) {
  if (what != HD_CURRENT_FORCE) return;
  if (n_forces < STANDIN_MAX) {
    forces[n_forces][0] = v[0]; forces[n_forces][1] = v[1]; forces[n_forces][2] = v[2];
    n_forces++;
  }
}
const char *hdGetString(HDenum what) { return what == HD_DEVICE_MODEL_TYPE ? "stand-in Touch" : ""; }
HDErrorInfo hdGetError(void) {
  HDErrorInfo e = {pending, 0, 1};
  pending = 0;
  return e;
}
const char *hdGetErrorString(HDerror e) {
  return e == HD_COMM_ERROR ? "Communication error" : e == HD_ILLEGAL_BEGIN ? "Illegal begin" : "Unknown error";
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
