/* Recording from C: into a file and through a write callback; every error of the three
 * recording functions; a failed write reported by the next step (which then does not run)
 * or by stop; the world locked while the write callback runs. The recording's contents are
 * checked in tests/recording.rs (Rust decoder) and tests/viewer.rs (the browser viewer). */
#include "hearth.h"
#include "ensure.h"

#include <stdint.h>
#include <stdlib.h>

/* A growable byte buffer the write callback appends to. */
typedef struct {
    uint8_t *data;
    size_t len, cap;
    int calls;
    int fail_after; /* fail on this call (1-based); 0 never */
    HearthWorld *world;
    HearthResult stop_inside, step_inside, read_inside;
} Sink;

static int32_t write_bytes(void *user_data, const uint8_t *bytes, size_t len) {
    Sink *s = (Sink *)user_data;
    s->calls++;
    if (s->world != NULL) {
        /* The world is locked while the callback runs: reads work, changes do not. */
        s->stop_inside = hearth_world_record_stop(s->world);
        s->step_inside = hearth_world_step(s->world, 1.0f / 60.0f);
        HearthWorldCounters c;
        s->read_inside = hearth_world_get_counters(s->world, &c);
    }
    if (s->fail_after != 0 && s->calls >= s->fail_after) {
        return -5;
    }
    if (s->len + len > s->cap) {
        size_t cap = (s->len + len) * 2;
        uint8_t *d = (uint8_t *)realloc(s->data, cap);
        if (d == NULL) {
            return 1;
        }
        s->data = d;
        s->cap = cap;
    }
    memcpy(s->data + s->len, bytes, len);
    s->len += len;
    return 0;
}

static int message_contains(const char *needle) {
    char msg[512];
    hearth_last_error_message(msg, sizeof msg);
    if (strstr(msg, needle) == NULL) {
        fprintf(stderr, "message \"%s\" lacks \"%s\"\n", msg, needle);
        return 0;
    }
    return 1;
}

static long file_size(const char *path) {
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return -1;
    }
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fclose(f);
    return n;
}

static void test_file(const char *path) {
    HearthWorld *w = new_world_on_ground();
    add_ball(w, 0, 3.0f, 42);
    HearthRecordDef def = hearth_record_def_default();
    ENSURE(def.record_contacts == 0 && def.write == NULL && def.user_data == NULL);
    def.record_contacts = 1;
    ENSURE_OK(hearth_world_record_start_file(w, path, &def));
    long start = file_size(path);
    ENSURE(start > 16); /* header, world, definitions and frame 0 are written at once */
    ENSURE_RESULT(hearth_world_record_start_file(w, path, &def), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_contains("already recording"));
    for (int i = 0; i < 30; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    long after = file_size(path);
    ENSURE(after > start + 30 * 60); /* a falling ball: at least its 31-byte record a step */
    ENSURE_OK(hearth_world_step(w, 0.0f)); /* dt 0 does nothing and records nothing */
    ENSURE(file_size(path) == after);
    ENSURE_OK(hearth_world_record_stop(w));
    ENSURE_RESULT(hearth_world_record_stop(w), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_contains("not recording"));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE(file_size(path) == after); /* stopped: nothing more */
    /* The header: magic and version 1. */
    FILE *f = fopen(path, "rb");
    unsigned char head[16] = {0};
    ENSURE(f != NULL && fread(head, 1, 16, f) == 16);
    if (f != NULL) {
        fclose(f);
    }
    ENSURE(memcmp(head, "HEARTHRC", 8) == 0);
    ENSURE(head[8] == 1 && head[9] == 0 && head[12] == 1); /* version 1, contacts flag */
    /* Destroying a recording world closes the file. */
    ENSURE_OK(hearth_world_record_start_file(w, path, &def));
    hearth_world_destroy(w);
    ENSURE(file_size(path) > 16);
    remove(path);
}

static void test_errors(const char *path) {
    HearthWorld *w = new_world_on_ground();
    HearthRecordDef def = hearth_record_def_default();
    ENSURE_RESULT(hearth_world_record_start_file(NULL, path, &def), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_contains("world"));
    ENSURE_RESULT(hearth_world_record_start_file(w, NULL, &def), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_contains("path"));
    ENSURE_RESULT(hearth_world_record_start_file(w, path, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_contains("def"));
    ENSURE_RESULT(hearth_world_record_start_file(w, "", &def), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_world_record_start_file(w, "/nonexistent-dir/x/rec.hrec", &def), HEARTH_ERROR_IO);
    ENSURE(message_contains("/nonexistent-dir/x/rec.hrec"));
    HearthRecordDef bad = def;
    bad.internal_value = 0;
    ENSURE_RESULT(hearth_world_record_start_file(w, path, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_contains("hearth_record_def"));
    ENSURE_RESULT(hearth_world_record_start_callback(w, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    bad = def;
    bad.record_contacts = 2;
    ENSURE_RESULT(hearth_world_record_start_file(w, path, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_contains("record_contacts"));
    bad = def;
    bad.write = write_bytes;
    ENSURE_RESULT(hearth_world_record_start_file(w, path, &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE(message_contains("def.write"));
    ENSURE_RESULT(hearth_world_record_start_callback(NULL, &def), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_record_start_callback(w, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_record_start_callback(w, &def), HEARTH_ERROR_NULL_POINTER);
    ENSURE(message_contains("def.write"));
    ENSURE_RESULT(hearth_world_record_stop(NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_record_stop(w), HEARTH_ERROR_INVALID_ARGUMENT);
    /* Nothing above started a recording or created a file. */
    ENSURE(file_size(path) == -1);
    ENSURE(strcmp(hearth_result_name(HEARTH_ERROR_IO), "HEARTH_ERROR_IO") == 0);
    hearth_world_destroy(w);
}

static void test_callback(void) {
    HearthWorld *w = new_world_on_ground();
    HearthBodyId ball = add_ball(w, 0, 3.0f, 42);
    Sink sink;
    memset(&sink, 0, sizeof sink);
    HearthRecordDef def = hearth_record_def_default();
    def.write = write_bytes;
    def.user_data = &sink;
    ENSURE_OK(hearth_world_record_start_callback(w, &def));
    ENSURE(sink.calls == 1 && sink.len > 16);
    ENSURE(sink.data != NULL && memcmp(sink.data, "HEARTHRC", 8) == 0);
    ENSURE_RESULT(hearth_world_record_start_callback(w, &def), HEARTH_ERROR_INVALID_ARGUMENT);
    sink.world = w; /* from now on the callback tries to change the world */
    for (int i = 0; i < 10; i++) {
        ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    }
    ENSURE(sink.calls == 11);
    ENSURE(sink.stop_inside == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(sink.step_inside == HEARTH_ERROR_WORLD_LOCKED);
    ENSURE(sink.read_inside == HEARTH_OK);
    /* The host's write fails on the next call: that step succeeds (it ran), the one after
     * reports the failure and does not run, then the world steps without recording. */
    sink.world = NULL;
    sink.fail_after = sink.calls + 1;
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthTransform before, after;
    ENSURE_OK(hearth_body_get_transform(w, ball, &before));
    ENSURE_RESULT(hearth_world_step(w, 1.0f / 60.0f), HEARTH_ERROR_IO);
    ENSURE(message_contains("returned -5"));
    ENSURE_OK(hearth_body_get_transform(w, ball, &after));
    ENSURE(before.position.y == after.position.y);
    int calls = sink.calls;
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE(sink.calls == calls);
    ENSURE_RESULT(hearth_world_record_stop(w), HEARTH_ERROR_INVALID_ARGUMENT);
    /* A failure pending at stop is reported by stop. */
    sink.fail_after = 0;
    ENSURE_OK(hearth_world_record_start_callback(w, &def));
    sink.fail_after = sink.calls + 1;
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE_RESULT(hearth_world_record_stop(w), HEARTH_ERROR_IO);
    ENSURE(message_contains("write callback"));
    ENSURE_RESULT(hearth_world_record_stop(w), HEARTH_ERROR_INVALID_ARGUMENT);
    /* A failing first write fails the start. */
    sink.fail_after = sink.calls + 1;
    ENSURE_RESULT(hearth_world_record_start_callback(w, &def), HEARTH_ERROR_IO);
    ENSURE_RESULT(hearth_world_record_stop(w), HEARTH_ERROR_INVALID_ARGUMENT);
    hearth_world_destroy(w);
    free(sink.data);
}

int main(int argc, char **argv) {
    (void)argc;
    /* A file next to this program, unique per build variant (they may run at once). */
    char path[1024];
    snprintf(path, sizeof path, "%s.hrec", argv[0]);
    remove(path);
    test_errors(path);
    test_file(path);
    test_callback();
    return ensure_report("test_record");
}
