/* Threads from C (issue 15): a pthread job system supplied through the world def's
 * enqueue/finish callbacks, the world's own threads, and an inline host all give the
 * single-threaded world's hash bit for bit; every def error; hearth_world_get_hash's errors;
 * a host that breaks the task contract gets HEARTH_ERROR_PANIC, never a crash. */
#include "hearth.h"
#include "ensure.h"

#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>

/* ------------------------------------------------------------ a pthread job system */
#define MAX_THREADS 8

typedef struct Job Job;
typedef struct {
    Job *job;
    uint32_t worker;
} Part;

struct Job {
    HearthTaskFn task;
    uint32_t count, min_range;
    void *task_context;
    uint32_t threads;
    pthread_t th[MAX_THREADS];
    Part parts[MAX_THREADS];
};

typedef struct {
    uint32_t threads;   /* threads per task (the world's worker_count) */
    int enqueued;       /* tasks handed over */
    int finished;       /* tasks waited for */
    int mode;           /* 0: correct; 1: drop the last range; 2: a worker index too large */
} Host;

/* Thread `worker` runs the chunks k with k % threads == worker, last first. */
static void *part_main(void *arg) {
    Part *p = (Part *)arg;
    Job *j = p->job;
    uint32_t chunk = j->min_range > 0 ? j->min_range : 1;
    uint32_t chunks = (j->count + chunk - 1) / chunk;
    for (uint32_t k = chunks; k-- > 0;) {
        if (k % j->threads != p->worker) continue;
        uint32_t start = k * chunk, end = start + chunk < j->count ? start + chunk : j->count;
        j->task(start, end, p->worker, j->task_context);
    }
    return NULL;
}

static void *host_enqueue(HearthTaskFn task, uint32_t count, uint32_t min_range, void *task_context, void *user) {
    Host *h = (Host *)user;
    h->enqueued++;
    if (h->mode == 1) {
        /* Broken: the last range never runs. */
        if (count > 1) task(0, count - 1, 0, task_context);
        return NULL;
    }
    if (h->mode == 2) {
        task(0, count, h->threads, task_context);
        return NULL;
    }
    Job *j = (Job *)calloc(1, sizeof(Job));
    j->task = task;
    j->count = count;
    j->min_range = min_range;
    j->task_context = task_context;
    j->threads = h->threads;
    for (uint32_t i = 0; i < j->threads; i++) {
        j->parts[i].job = j;
        j->parts[i].worker = i;
        pthread_create(&j->th[i], NULL, part_main, &j->parts[i]);
    }
    return j;
}

static void host_finish(void *user_task, void *user) {
    Host *h = (Host *)user;
    Job *j = (Job *)user_task;
    for (uint32_t i = 0; i < j->threads; i++) pthread_join(j->th[i], NULL);
    free(j);
    h->finished++;
}

/* A host that runs each task at once on the calling thread and returns NULL. */
static void *inline_enqueue(HearthTaskFn task, uint32_t count, uint32_t min_range, void *task_context, void *user) {
    (void)min_range;
    (*(int *)user)++;
    task(0, count, 0, task_context);
    return NULL;
}
static void never_finish(void *user_task, void *user) {
    (void)user_task;
    (void)user;
    ENSURE(0); /* enqueue returned NULL: finish must not be called */
}

/* ------------------------------------------------------------ the scene */
/* 400 bodies, spheres and boxes alternating, dropped in a 20 x 20 grid onto a plane. */
static void build(HearthWorld *w) {
    new_ground(w);
    HearthShapeDef sd = hearth_shape_def_default();
    HearthShapeId sh = {0, 0};
    for (int i = 0; i < 400; i++) {
        HearthBodyDef bd = hearth_body_def_default();
        bd.type = HEARTH_BODY_DYNAMIC;
        bd.transform.position.x = (float)(i % 20) * 1.05f - 10.0f;
        bd.transform.position.y = 0.5f + (float)(i / 20 % 4) * 1.1f;
        bd.transform.position.z = (float)(i / 80) * 1.05f + 0.1f * (float)(i % 3);
        HearthBodyId b = {0, 0};
        ENSURE_OK(hearth_body_create(w, &bd, &b));
        if (i % 2 == 0) {
            HearthSphere s = {{0, 0, 0}, 0.5f};
            ENSURE_OK(hearth_shape_create_sphere(w, b, &sd, &s, &sh));
        } else {
            HearthBox x = {{0, 0, 0}, {0, 0, 0, 1}, {0.5f, 0.5f, 0.5f}};
            ENSURE_OK(hearth_shape_create_box(w, b, &sd, &x, &sh));
        }
    }
}

static uint64_t run(const HearthWorldDef *def, int steps) {
    HearthWorld *w = NULL;
    ENSURE_OK(hearth_world_create(def, &w));
    if (!w) return 0;
    build(w);
    for (int i = 0; i < steps; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    uint64_t hash = 0;
    ENSURE_OK(hearth_world_get_hash(w, &hash));
    hearth_world_destroy(w);
    return hash;
}

static int message_names(const char *word) {
    char msg[512];
    hearth_last_error_message(msg, sizeof msg);
    return strstr(msg, word) != NULL;
}

int main(void) {
    const int steps = 40;
    HearthWorldDef serial = hearth_world_def_default();
    ENSURE(serial.worker_count == 1 && serial.enqueue_task == NULL && serial.finish_task == NULL &&
           serial.user_task_context == NULL);
    uint64_t want = run(&serial, steps);
    ENSURE(want == run(&serial, steps)); /* twice in a process */

    /* The world's own threads. */
    for (uint32_t n = 2; n <= 4; n++) {
        HearthWorldDef d = hearth_world_def_default();
        d.worker_count = n;
        ENSURE(run(&d, steps) == want);
    }

    /* The pthread host at 2 to 4 workers. */
    for (uint32_t n = 2; n <= 4; n++) {
        Host host = {n, 0, 0, 0};
        HearthWorldDef d = hearth_world_def_default();
        d.worker_count = n;
        d.enqueue_task = host_enqueue;
        d.finish_task = host_finish;
        d.user_task_context = &host;
        ENSURE(run(&d, steps) == want);
        ENSURE(host.enqueued > 0 && host.enqueued == host.finished);
    }

    /* A host that runs tasks inline (enqueue returns NULL: finish is never called). */
    {
        int calls = 0;
        HearthWorldDef d = hearth_world_def_default();
        d.worker_count = 2;
        d.enqueue_task = inline_enqueue;
        d.finish_task = never_finish;
        d.user_task_context = &calls;
        ENSURE(run(&d, steps) == want);
        ENSURE(calls > 0);
    }

    /* The hash changes as the world moves, and its errors. */
    {
        HearthWorld *w = NULL;
        ENSURE_OK(hearth_world_create(&serial, &w));
        build(w);
        uint64_t h0 = 0, h1 = 0, out = 0xA5A5A5A5A5A5A5A5ull;
        ENSURE_OK(hearth_world_get_hash(w, &h0));
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
        ENSURE_OK(hearth_world_get_hash(w, &h1));
        ENSURE(h0 != h1);
        ENSURE_RESULT(hearth_world_get_hash(NULL, &out), HEARTH_ERROR_NULL_POINTER);
        ENSURE(out == 0xA5A5A5A5A5A5A5A5ull);
        ENSURE(message_names("world"));
        ENSURE_RESULT(hearth_world_get_hash(w, NULL), HEARTH_ERROR_NULL_POINTER);
        ENSURE(message_names("out_hash"));
        hearth_world_destroy(w);
    }

    /* Every def error: nothing is created, the out pointer is unwritten. */
    {
        HearthWorld *sentinel = (HearthWorld *)(uintptr_t)0x1234;
        uint32_t bad_counts[] = {0, 65, 1000, UINT32_MAX};
        for (size_t i = 0; i < sizeof bad_counts / sizeof bad_counts[0]; i++) {
            HearthWorldDef d = hearth_world_def_default();
            d.worker_count = bad_counts[i];
            HearthWorld *w = sentinel;
            ENSURE_RESULT(hearth_world_create(&d, &w), HEARTH_ERROR_INVALID_ARGUMENT);
            ENSURE(message_names("worker_count"));
            ENSURE(w == sentinel);
        }
        Host host = {2, 0, 0, 0};
        HearthWorldDef d = hearth_world_def_default();
        d.worker_count = 2;
        d.enqueue_task = host_enqueue;
        d.user_task_context = &host;
        HearthWorld *w = sentinel;
        ENSURE_RESULT(hearth_world_create(&d, &w), HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE(message_names("finish_task") && w == sentinel);
        d.enqueue_task = NULL;
        d.finish_task = host_finish;
        ENSURE_RESULT(hearth_world_create(&d, &w), HEARTH_ERROR_INVALID_ARGUMENT);
        ENSURE(message_names("enqueue_task") && w == sentinel);
        ENSURE(host.enqueued == 0);
    }

    /* A host that breaks the contract: the step reports HEARTH_ERROR_PANIC (no crash, no
     * unwinding through the host) and the world refuses further steps. */
    for (int mode = 1; mode <= 2; mode++) {
        Host host = {2, 0, 0, mode};
        HearthWorldDef d = hearth_world_def_default();
        d.worker_count = 2;
        d.enqueue_task = host_enqueue;
        d.finish_task = host_finish;
        d.user_task_context = &host;
        HearthWorld *w = NULL;
        ENSURE_OK(hearth_world_create(&d, &w));
        build(w);
        HearthResult r = HEARTH_OK;
        for (int i = 0; i < 5 && r == HEARTH_OK; i++) r = hearth_world_step(w, 1.0f / 60.0f);
        ENSURE(r == HEARTH_ERROR_PANIC);
        ENSURE(message_names(mode == 1 ? "exactly once" : "worker"));
        ENSURE_RESULT(hearth_world_step(w, 1.0f / 60.0f), HEARTH_ERROR_PANIC);
        uint64_t h = 0;
        ENSURE_OK(hearth_world_get_hash(w, &h)); /* reads still work */
        hearth_world_destroy(w);
    }

    return ensure_report("test_threads");
}
