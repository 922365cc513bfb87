/* A stand-in for the Force Dimension SDK's libdhd.so, for haphe's tests: the functions
 * haphe calls, with dhdc.h's C signatures, over simulated mechanisms (up to STANDIN_DEVICES
 * of them, each with its own state, as several devices on one PC) whose end points follow
 * scripted trajectories (one sample per dhdGetPosition call), recording every force
 * written. dhdOpen opens the first device not yet open, dhdOpenID the one at an index; the
 * ID returned is the index. Test-only symbols (standin_*) script them and read them back:
 * those without _of act on device 0. */
#include <stdlib.h>
#include <string.h>

#include "env.h"

#define STANDIN_MAX 400000
#define STANDIN_DEVICES 4
#define DHD_ERROR_COM 5
#define DHD_ERROR_INVALID_INDEX 16

struct standin_device {
  double samples[STANDIN_MAX][6]; /* position, velocity, metres and m/s */
  int n_samples;
  int current;
  double forces[STANDIN_MAX][3];
  int n_forces;
  int fail_from; /* dhdGetPosition call from which the device is unplugged */
  int opened;
  int force_enabled;
  int calls;
};

static struct standin_device dev[STANDIN_DEVICES];
static int devices = 1;
static int last_error = 0;
/* Whether the state was set up: by standin_reset, or with one device at the first call
 * (a process that runs haphe scripts it through the environment only); the number of
 * devices connected is then HAPHE_STANDIN_DEVICES's, 1 by default. */
static int ready = 0;
void standin_reset(int device_count);
static void init(void) {
  const char *n = getenv("HAPHE_STANDIN_DEVICES");
  if (!ready) standin_reset(1);
  /* Read at every call: a process may load the stand-in before it sets the variable. */
  if (n) devices = atoi(n) < STANDIN_DEVICES ? atoi(n) : STANDIN_DEVICES;
}

static void reset_device(struct standin_device *d) {
  d->n_samples = 0; d->current = -1; d->n_forces = 0; d->fail_from = -1; d->opened = 0;
  d->force_enabled = 0; d->calls = 0;
}

void standin_reset(int device_count) {
  for (int i = 0; i < STANDIN_DEVICES; i++) reset_device(&dev[i]);
  devices = device_count < STANDIN_DEVICES ? device_count : STANDIN_DEVICES;
  last_error = 0; n_button_masks = 0; ready = 1;
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
void standin_fail_from_of(int i, int call) { if (of(i)) dev[i].fail_from = call; }
void standin_fail_from(int call) { standin_fail_from_of(0, call); }
int standin_forces_of(int i, double *out, int max) {
  struct standin_device *d = of(i);
  if (!d) return 0;
  int n = d->n_forces < max ? d->n_forces : max;
  memcpy(out, d->forces, sizeof(double) * 3 * (size_t)n);
  return d->n_forces;
}
int standin_forces(double *out, int max) { return standin_forces_of(0, out, max); }
int standin_force_enabled_of(int i) { return of(i) ? dev[i].force_enabled : 0; }
int standin_force_enabled(void) { return standin_force_enabled_of(0); }
int standin_opened_of(int i) { return of(i) ? dev[i].opened : 0; }
int standin_opened(void) { return standin_opened_of(0); }

int dhdGetDeviceCount(void) { init(); return devices; }
int dhdOpenID(char index) {
  int i = (int)index;
  init();
  if (i < 0 || i >= devices) { last_error = DHD_ERROR_INVALID_INDEX; return -1; }
  struct standin_device *d = &dev[i];
  if (d->opened) { last_error = DHD_ERROR_COM; return -1; }
  d->opened = 1;
  int n = standin_env_path(i, d->samples, STANDIN_MAX);
  if (n >= 0) { d->n_samples = n; d->current = -1; d->n_forces = 0; d->calls = 0; }
  int fail = standin_env_int("HAPHE_STANDIN_FAIL_FROM", i);
  if (fail >= 0) d->fail_from = fail;
  return i;
}
int dhdOpen(void) {
  init();
  for (int i = 0; i < devices; i++)
    if (!dev[i].opened) return dhdOpenID((char)i);
  last_error = DHD_ERROR_COM;
  return -1;
}
static struct standin_device *open_device(char id) {
  struct standin_device *d = of((int)id);
  if (!d || !d->opened) { last_error = DHD_ERROR_COM; return NULL; }
  return d;
}
int dhdClose(char id) {
  struct standin_device *d = of((int)id);
  if (!d) return -1;
  standin_env_report((int)id, d->forces, d->n_forces, STANDIN_MAX, d->force_enabled);
  d->opened = 0;
  return 0;
}
const char *dhdGetSystemName(char id) {
  static const char *names[STANDIN_DEVICES] = {"stand-in omega.3", "stand-in sigma.7", "stand-in delta.3", "stand-in lambda.7"};
  return open_device(id) ? names[(int)id] : NULL;
}
int dhdEnableForce(unsigned char val, char id) {
  struct standin_device *d = open_device(id);
  if (!d) return -1;
  d->force_enabled = val;
  return 0;
}
int dhdGetPosition(double *px, double *py, double *pz, char id) {
  struct standin_device *d = open_device(id);
  if (!d) return -1;
  if (d->fail_from >= 0 && d->calls >= d->fail_from) { last_error = DHD_ERROR_COM; return -1; }
  d->calls++;
  if (d->current + 1 < d->n_samples) d->current++;
  if (d->current < 0) { *px = *py = 0.0; *pz = 1.0; return 0; }
  *px = d->samples[d->current][0]; *py = d->samples[d->current][1]; *pz = d->samples[d->current][2];
  return 0;
}
int dhdGetLinearVelocity(double *vx, double *vy, double *vz, char id) {
  struct standin_device *d = open_device(id);
  if (!d) return -1;
  if (d->current < 0) { *vx = *vy = *vz = 0.0; return 0; }
  *vx = d->samples[d->current][3]; *vy = d->samples[d->current][4]; *vz = d->samples[d->current][5];
  return 0;
}
unsigned int dhdGetButtonMask(char id) {
  struct standin_device *d = of((int)id);
  /* The scripted buttons are device 0's. */
  return d && id == 0 ? standin_buttons_at(d->current) : 0u;
}
int dhdSetForce(double fx, double fy, double fz, char id) {
  struct standin_device *d = open_device(id);
  if (!d) return -1;
  if (d->n_forces < STANDIN_MAX) {
    d->forces[d->n_forces][0] = fx; d->forces[d->n_forces][1] = fy; d->forces[d->n_forces][2] = fz;
    d->n_forces++;
  }
  return 0;
}
double dhdGetMaxForce(char id) { (void)id; return 3.3; }
int dhdErrorGetLast(void) { return last_error; }
const char *dhdErrorGetStr(int error) {
  return error == DHD_ERROR_COM ? "communication error between the host and the haptic device"
       : error == DHD_ERROR_INVALID_INDEX ? "invalid index" : "no error";
}
const char *dhdErrorGetLastStr(void) { return dhdErrorGetStr(last_error); }
