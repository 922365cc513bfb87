/* Scripting a stand-in from the environment, for tests that run haphe as another process
 * (the in-process tests use the standin_* functions instead):
 * - HAPHE_STANDIN_PATH names a text file of samples, one a line: six numbers (position and
 *   velocity, in the library's units and frame) and optionally a seventh, the buttons held
 *   (a bit mask), read each time the device is opened (the path then starts again;
 *   standin_env_path returns -1 without the variable);
 * - HAPHE_STANDIN_FORCES names a file that receives, when the device is closed, one line:
 *   the number of forces written, the last force (three numbers), whether force output
 *   was still enabled (1 or 0) and the largest force magnitude written.
 * - HAPHE_STANDIN_FAIL_FROM names the read (Force Dimension) or frame (OpenHaptics) from
 *   which the device is unplugged (each fails with a communication error), counted from
 *   its opening.
 * Those are device 0's; device i > 0 of a stand-in with several reads and writes the files
 * of HAPHE_STANDIN_PATH_i and HAPHE_STANDIN_FORCES_i, and fails from
 * HAPHE_STANDIN_FAIL_FROM_i (and its buttons are none). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The buttons held at each sample, one bit mask per sample (none held beyond those set):
 * scripted by the test-only standin_set_buttons, cleared by standin_reset. */
#define STANDIN_BUTTONS_MAX 400000
static unsigned int button_masks[STANDIN_BUTTONS_MAX];
static int n_button_masks = 0;

int standin_set_buttons(const unsigned int *masks, int n) {
  if (n > STANDIN_BUTTONS_MAX) n = STANDIN_BUTTONS_MAX;
  memcpy(button_masks, masks, sizeof(unsigned int) * (size_t)n);
  n_button_masks = n;
  return n;
}

static unsigned int standin_buttons_at(int sample) {
  return sample >= 0 && sample < n_button_masks ? button_masks[sample] : 0u;
}

/* The variable `base` of device `device`: `base` itself for device 0, else `base_i`. */
static const char *standin_env(const char *base, int device) {
  char variable[64];
  if (device == 0) return getenv(base);
  snprintf(variable, sizeof variable, "%s_%d", base, device);
  return getenv(variable);
}

/* The number in the variable `base` of device `device`, or -1. */
static int standin_env_int(const char *base, int device) {
  const char *value = standin_env(base, device);
  return value ? atoi(value) : -1;
}

static int standin_env_path(int device, double (*samples)[6], int max) {
  const char *name = standin_env("HAPHE_STANDIN_PATH", device);
  FILE *f = name ? fopen(name, "r") : NULL;
  int n = 0;
  if (!name) return -1;
  if (!f) return 0;
  char line[1024];
  while (n < max && fgets(line, sizeof line, f)) {
    unsigned int mask = 0;
    int got = sscanf(line, "%lf %lf %lf %lf %lf %lf %u", &samples[n][0], &samples[n][1],
                     &samples[n][2], &samples[n][3], &samples[n][4], &samples[n][5], &mask);
    if (got < 6) break;
    if (device == 0 && n < STANDIN_BUTTONS_MAX) button_masks[n] = got == 7 ? mask : 0u;
    n++;
  }
  if (device == 0) n_button_masks = n < STANDIN_BUTTONS_MAX ? n : STANDIN_BUTTONS_MAX;
  fclose(f);
  return n;
}

static void standin_env_report(int device, double (*forces)[3], int n, int max, int enabled) {
  const char *name = standin_env("HAPHE_STANDIN_FORCES", device);
  FILE *f = name ? fopen(name, "w") : NULL;
  int last = (n < max ? n : max) - 1;
  double largest = 0.0;
  if (!f) return;
  for (int i = 0; i <= last; i++) {
    double m = sqrt(forces[i][0] * forces[i][0] + forces[i][1] * forces[i][1] + forces[i][2] * forces[i][2]);
    if (m > largest) largest = m;
  }
  if (last < 0) fprintf(f, "0 nan nan nan %d 0\n", enabled);
  else fprintf(f, "%d %.17g %.17g %.17g %d %.17g\n", n, forces[last][0], forces[last][1], forces[last][2], enabled, largest);
  fclose(f);
}
