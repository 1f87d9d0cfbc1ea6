/* calibrate.c — the calibration workload (calibrate.h). */
#include "run/calibrate.h"
#include "run/gl_context.h"
#include "core/dm_error.h"
#include "core/dm_proc.h"

#include <epoxy/gl.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#define CALIBRATE_KERNEL_ROUNDS (1u << 22)
/* The kernel around each round of samples: a quarter of the start and end
 * kernel (about 2.5 ms on the CI machine).  Its times are read only
 * against each other within the run (models/drift.h, the calibration
 * predictor), never against another run's or the start and end figures. */
#define CALIBRATE_ROUND_KERNEL_ROUNDS (1u << 20)
#define CALIBRATE_SIZE 256

/* One run of the kernel: a xorshift generator feeding a floating-point
 * recurrence whose result is kept, so neither can be optimised away. */
static double calibrate__kernel(uint32_t rounds)
{
    uint64_t x = 0x9e3779b97f4a7c15ull;
    double acc = 0.0;
    for (uint32_t i = 0; i < rounds; i++) {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        acc = acc * 0.999999 + (double)(x >> 40) * 1e-9;
    }
    return acc;
}

/* The shortest of n timings: noise on a shared machine only adds time, so
 * the minimum is the machine's own speed; time-slicing by other processes
 * is what compare's contention check (WallTime against CPUTime) names. */
static double calibrate__min(const double *t, size_t n)
{
    double m = t[0];
    for (size_t i = 1; i < n; i++)
        m = fmin(m, t[i]);
    return m;
}

static const char calibrate__vs[] =
    "#version 450 core\n"
    "out vec2 uv;\n"
    "void main() {\n"
    "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
    "    uv = p;\n"
    "    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);\n"
    "}\n";

static const char calibrate__fs[] =
    "#version 450 core\n"
    "in vec2 uv;\n"
    "out vec4 colour;\n"
    "void main() {\n"
    "    vec2 p = uv;\n"
    "    for (int i = 0; i < 16; i++)\n"
    "        p = fract(vec2(sin(p.x * 12.9898 + p.y), cos(p.y * 78.233 - p.x)) * 43.7585);\n"
    "    colour = vec4(p, 0.5, 1.0);\n"
    "}\n";

static GLuint calibrate__shader(GLenum type, const char *src)
{
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        glDeleteShader(s);
        return 0;
    }
    return s;
}

/* The draw's shortest time, or NaN when its program does not build. */
static double calibrate__draw(void)
{
    GLuint vs = calibrate__shader(GL_VERTEX_SHADER, calibrate__vs);
    GLuint fs = calibrate__shader(GL_FRAGMENT_SHADER, calibrate__fs);
    GLuint prog = glCreateProgram(), vao = 0, tex = 0, fbo = 0;
    GLint linked = 0;
    if (vs && fs) {
        glAttachShader(prog, vs);
        glAttachShader(prog, fs);
        glLinkProgram(prog);
        glGetProgramiv(prog, GL_LINK_STATUS, &linked);
    }
    double t[CALIBRATE_REPS], med = NAN;
    if (linked) {
        glCreateVertexArrays(1, &vao);
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, GL_RGBA8, CALIBRATE_SIZE, CALIBRATE_SIZE);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, CALIBRATE_SIZE, CALIBRATE_SIZE);
        glUseProgram(prog);
        glBindVertexArray(vao);
        for (int i = 0; i < CALIBRATE_WARMUP + CALIBRATE_REPS; i++) {
            int64_t t0 = dm_now_ns();
            glClear(GL_COLOR_BUFFER_BIT);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glFinish();
            if (i >= CALIBRATE_WARMUP)
                t[i - CALIBRATE_WARMUP] = (double)(dm_now_ns() - t0);
        }
        med = glGetError() == GL_NO_ERROR ? calibrate__min(t, CALIBRATE_REPS) : NAN;
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &tex);
        glDeleteVertexArrays(1, &vao);
    }
    glDeleteProgram(prog);
    glDeleteShader(vs);
    glDeleteShader(fs);
    return med;
}

void calibrate_measure(int gl_current, calibrate_result *out)
{
    volatile double sink = 0;
    double t[CALIBRATE_REPS];
    for (int i = 0; i < CALIBRATE_WARMUP + CALIBRATE_REPS; i++) {
        int64_t t0 = dm_now_ns();
        sink += calibrate__kernel(CALIBRATE_KERNEL_ROUNDS);
        if (i >= CALIBRATE_WARMUP)
            t[i - CALIBRATE_WARMUP] = (double)(dm_now_ns() - t0);
    }
    (void)sink;
    out->cpu_ns = calibrate__min(t, CALIBRATE_REPS);
    out->draw_ns = gl_current ? calibrate__draw() : NAN;
}

double calibrate_cpu_once(void)
{
    volatile double sink = 0;
    int64_t t0 = dm_now_ns();
    sink += calibrate__kernel(CALIBRATE_ROUND_KERNEL_ROUNDS);
    (void)sink;
    return (double)(dm_now_ns() - t0);
}

int calibrate_in_child(calibrate_result *out)
{
    out->cpu_ns = out->draw_ns = NAN;
    int fds[2];
    if (pipe(fds) != 0)
        return DM_ERR_CHILD;
    pid_t pid = dm_proc_fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return DM_ERR_CHILD;
    }
    if (pid == 0) {
        close(fds[0]);
        gl_context *gl = NULL;
        dm_str err = {0};
        int have_gl = gl_context_create(NULL, &gl, &err) == 0;
        calibrate_result r;
        calibrate_measure(have_gl, &r);
        char line[96];
        int n = snprintf(line, sizeof line, "%.0f %.0f\n", r.cpu_ns, r.draw_ns);
        ssize_t w = write(fds[1], line, (size_t)n);
        (void)w;
        _exit(0);
    }
    close(fds[1]);
    char buf[96] = "";
    size_t len = 0;
    struct pollfd pfd = { fds[0], POLLIN, 0 };
    while (len + 1 < sizeof buf && poll(&pfd, 1, 60000) > 0) {
        ssize_t n = read(fds[0], buf + len, sizeof buf - 1 - len);
        if (n <= 0)
            break;
        len += (size_t)n;
    }
    buf[len] = '\0';
    close(fds[0]);
    kill(pid, SIGKILL);
    dm_proc_wait(pid, NULL);
    double cpu = NAN, draw = NAN;
    if (sscanf(buf, "%lf %lf", &cpu, &draw) < 1)
        return DM_ERR_CHILD;
    out->cpu_ns = cpu;
    out->draw_ns = draw;
    return 0;
}
