/* Snapshots from C: size, save into a caller-owned buffer, restore into the same world and a
 * fresh one, after which stepping reproduces the original bit for bit; ids preserved; every
 * error (NULLs, a buffer too small with the size needed reported, truncated, bit-flipped,
 * another version) refused with the world unchanged. */
#include "hearth.h"
#include "ensure.h"

#include <stdint.h>
#include <stdlib.h>

/* The world's snapshot in a malloc'd buffer (the caller frees it). */
static uint8_t *save(const HearthWorld *w, size_t *out_size) {
    size_t size = 0, written = 0;
    ENSURE_OK(hearth_world_snapshot_size(w, &size));
    uint8_t *buf = (uint8_t *)malloc(size);
    ENSURE_OK(hearth_world_snapshot_save(w, buf, size, &written));
    ENSURE(written == size);
    *out_size = size;
    return buf;
}

static int same_snapshot(const HearthWorld *w, const uint8_t *bytes, size_t size) {
    size_t n = 0;
    uint8_t *now = save(w, &n);
    int same = n == size && memcmp(now, bytes, size) == 0;
    free(now);
    return same;
}

static size_t g_recorded;
static int32_t count_bytes(void *user_data, const uint8_t *bytes, size_t len) {
    (void)bytes;
    *(size_t *)user_data += len;
    return 0;
}

static int g_force_calls;
static void count_force(void *user_data, HearthWorld *world, const HearthGeneratorContext *ctx) {
    (void)world;
    (void)ctx;
    *(int *)user_data += 1;
}
static void no_contacts(void *user_data, HearthWorld *world, const HearthGeneratorContext *ctx,
                        HearthContactSink *sink) {
    (void)user_data;
    (void)world;
    (void)ctx;
    (void)sink;
}

/* User generators: kept in the same world; in a fresh one listed as missing, skipped by the
 * step, and set again by the host. */
static void user_generators(void) {
    HearthWorld *w = new_world_on_ground();
    add_ball(w, 0, 2, 0);
    HearthUserForceGeneratorDef fd = hearth_user_force_generator_def_default();
    fd.callback = count_force;
    fd.user_data = &g_force_calls;
    HearthGeneratorId force = {0, 0}, contact = {0, 0}, gravity = {0, 0};
    ENSURE_OK(hearth_generator_create_user_force(w, &fd, &force));
    HearthUserContactGeneratorDef cd = hearth_user_contact_generator_def_default();
    cd.callback = no_contacts;
    ENSURE_OK(hearth_generator_create_user_contact(w, &cd, &contact));
    HearthGravityGeneratorDef gd = hearth_gravity_generator_def_default();
    ENSURE_OK(hearth_generator_create_gravity(w, &gd, &gravity));
    size_t size = 0;
    uint8_t *snap = save(w, &size);

    g_force_calls = 0;
    ENSURE_OK(hearth_world_snapshot_restore(w, snap, size));
    ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    ENSURE(g_force_calls == 1); /* same world: the callback kept */
    size_t missing = 9;
    ENSURE_OK(hearth_world_get_user_generators_missing_callback(w, NULL, 0, &missing));
    ENSURE(missing == 0);

    HearthWorldDef wd = hearth_world_def_default();
    HearthWorld *fresh = NULL;
    ENSURE_OK(hearth_world_create(&wd, &fresh));
    ENSURE_OK(hearth_world_snapshot_restore(fresh, snap, size));
    ENSURE_OK(hearth_world_step(fresh, 1.0f / 60.0f));
    ENSURE(g_force_calls == 1); /* no callback: skipped */
    ENSURE_OK(hearth_world_get_user_generators_missing_callback(fresh, NULL, 0, &missing));
    ENSURE(missing == 2);
    HearthGeneratorId ids[2] = {{7, 7}, {7, 7}};
    size_t got = 5;
    ENSURE_RESULT(hearth_world_get_user_generators_missing_callback(fresh, ids, 1, &got), HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(got == 5 && ids[0].index == 7);
    ENSURE_RESULT(hearth_world_get_user_generators_missing_callback(NULL, ids, 2, &got), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_user_generators_missing_callback(fresh, NULL, 2, &got), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_get_user_generators_missing_callback(fresh, ids, 2, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_OK(hearth_world_get_user_generators_missing_callback(fresh, ids, 2, &got));
    ENSURE(got == 2 && ids[0].index == force.index && ids[1].index == contact.index);
    uint32_t type = 0;
    ENSURE_OK(hearth_generator_get_type(fresh, ids[0], &type));
    ENSURE(type == HEARTH_GENERATOR_USER_FORCE);

    /* Setter errors. */
    ENSURE_RESULT(hearth_generator_set_user_force_callback(NULL, ids[0], &fd), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_set_user_force_callback(fresh, ids[0], NULL), HEARTH_ERROR_NULL_POINTER);
    HearthUserForceGeneratorDef bad = fd;
    bad.callback = NULL;
    ENSURE_RESULT(hearth_generator_set_user_force_callback(fresh, ids[0], &bad), HEARTH_ERROR_NULL_POINTER);
    bad = fd;
    bad.internal_value = 0;
    ENSURE_RESULT(hearth_generator_set_user_force_callback(fresh, ids[0], &bad), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_generator_set_user_force_callback(fresh, ids[1], &fd), HEARTH_ERROR_INVALID_ARGUMENT);
    ENSURE_RESULT(hearth_generator_set_user_force_callback(fresh, force, &fd), HEARTH_ERROR_INVALID_ID);
    HearthGeneratorId none = {0, 0};
    ENSURE_RESULT(hearth_generator_set_user_force_callback(fresh, none, &fd), HEARTH_ERROR_INVALID_ID);
    ENSURE_RESULT(hearth_generator_set_user_contact_callback(NULL, ids[1], &cd), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_set_user_contact_callback(fresh, ids[1], NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_set_user_contact_callback(fresh, ids[0], &cd), HEARTH_ERROR_INVALID_ARGUMENT);
    HearthUserContactGeneratorDef cbad = cd;
    cbad.capacity = 1048577;
    ENSURE_RESULT(hearth_generator_set_user_contact_callback(fresh, ids[1], &cbad), HEARTH_ERROR_INVALID_ARGUMENT);
    cbad = cd;
    cbad.callback = NULL;
    ENSURE_RESULT(hearth_generator_set_user_contact_callback(fresh, ids[1], &cbad), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_generator_set_user_contact_callback(fresh, contact, &cd), HEARTH_ERROR_INVALID_ID);
    ENSURE_OK(hearth_world_get_user_generators_missing_callback(fresh, NULL, 0, &missing));
    ENSURE(missing == 2); /* the failures set nothing */

    ENSURE_OK(hearth_generator_set_user_force_callback(fresh, ids[0], &fd));
    ENSURE_OK(hearth_generator_set_user_contact_callback(fresh, ids[1], &cd));
    ENSURE_OK(hearth_world_get_user_generators_missing_callback(fresh, NULL, 0, &missing));
    ENSURE(missing == 0);
    ENSURE_OK(hearth_world_step(fresh, 1.0f / 60.0f));
    ENSURE(g_force_calls == 2);
    (void)gravity;
    free(snap);
    hearth_world_destroy(fresh);
    hearth_world_destroy(w);
}

static int same_transform(HearthTransform a, HearthTransform b) { return memcmp(&a, &b, sizeof a) == 0; }

int main(void) {
    HearthWorld *w = new_world_on_ground();
    HearthBodyId balls[6];
    for (int i = 0; i < 6; i++) balls[i] = add_ball(w, (float)i * 0.3f, 1.0f + 1.1f * (float)i, 0);
    for (int i = 0; i < 30; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));

    size_t size = 0;
    uint8_t *snap = save(w, &size);
    ENSURE(size > 28);

    /* Step 40 frames, remember the poses; restore; step again: bit for bit the same, and the
     * old handles address the same bodies. */
    for (int i = 0; i < 40; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    HearthTransform first[6];
    for (int i = 0; i < 6; i++) ENSURE_OK(hearth_body_get_transform(w, balls[i], &first[i]));
    size_t after_size = 0;
    uint8_t *after = save(w, &after_size);
    HearthBodyId extra = add_ball(w, 5, 5, 0);
    ENSURE_OK(hearth_world_snapshot_restore(w, snap, size));
    ENSURE(same_snapshot(w, snap, size)); /* save, restore, save: the same bytes */
    HearthTransform tmp;
    ENSURE_RESULT(hearth_body_get_transform(w, extra, &tmp), HEARTH_ERROR_INVALID_ID);
    HearthBodyId extra_again = add_ball(w, 5, 5, 0);
    ENSURE(extra_again.index == extra.index && extra_again.generation == extra.generation);
    ENSURE_OK(hearth_body_destroy(w, extra_again));
    ENSURE_OK(hearth_world_snapshot_restore(w, snap, size));
    for (int i = 0; i < 40; i++) ENSURE_OK(hearth_world_step(w, 1.0f / 60.0f));
    for (int i = 0; i < 6; i++) {
        HearthTransform t;
        ENSURE_OK(hearth_body_get_transform(w, balls[i], &t));
        ENSURE(same_transform(t, first[i]));
    }
    ENSURE(same_snapshot(w, after, after_size));

    /* Into a fresh world: the same bytes, and the same future. */
    HearthWorldDef wd = hearth_world_def_default();
    wd.substeps = 2; /* replaced by the snapshot's settings */
    HearthWorld *fresh = NULL;
    ENSURE_OK(hearth_world_create(&wd, &fresh));
    ENSURE_OK(hearth_world_snapshot_restore(fresh, snap, size));
    ENSURE(same_snapshot(fresh, snap, size));
    for (int i = 0; i < 40; i++) ENSURE_OK(hearth_world_step(fresh, 1.0f / 60.0f));
    ENSURE(same_snapshot(fresh, after, after_size));

    /* A running recording is not part of a snapshot: a restore neither stops nor restarts it. */
    {
        HearthRecordDef rd = hearth_record_def_default();
        rd.write = count_bytes;
        rd.user_data = &g_recorded;
        ENSURE_OK(hearth_world_record_start_callback(fresh, &rd));
        const size_t before = g_recorded;
        ENSURE_OK(hearth_world_snapshot_restore(fresh, snap, size));
        ENSURE(g_recorded == before);
        ENSURE_OK(hearth_world_step(fresh, 1.0f / 60.0f));
        ENSURE(g_recorded > before);
        ENSURE_OK(hearth_world_record_stop(fresh));
    }

    /* Errors. Sizes and saves. */
    size_t n = 7;
    ENSURE_RESULT(hearth_world_snapshot_size(NULL, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_snapshot_size(w, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE(n == 7);
    uint8_t *buf = (uint8_t *)malloc(after_size);
    memset(buf, 0xA5, after_size);
    n = 0;
    ENSURE_RESULT(hearth_world_snapshot_save(w, buf, after_size - 1, &n), HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(n == after_size); /* the size needed */
    ENSURE(buf[0] == 0xA5 && buf[after_size - 1] == 0xA5);
    n = 0;
    ENSURE_RESULT(hearth_world_snapshot_save(w, NULL, 0, &n), HEARTH_ERROR_BUFFER_TOO_SMALL);
    ENSURE(n == after_size);
    ENSURE_RESULT(hearth_world_snapshot_save(NULL, buf, after_size, &n), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_snapshot_save(w, buf, after_size, NULL), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_snapshot_save(w, NULL, after_size, &n), HEARTH_ERROR_NULL_POINTER);

    /* Restores that fail leave the world unchanged. */
    ENSURE_RESULT(hearth_world_snapshot_restore(NULL, snap, size), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_snapshot_restore(w, NULL, size), HEARTH_ERROR_NULL_POINTER);
    ENSURE_RESULT(hearth_world_snapshot_restore(w, NULL, 0), HEARTH_ERROR_INVALID_ARGUMENT);
    for (size_t len = 0; len < size; len += 1 + len / 8)
        ENSURE_RESULT(hearth_world_snapshot_restore(w, snap, len), HEARTH_ERROR_INVALID_ARGUMENT);
    uint8_t *bad = (uint8_t *)malloc(size);
    uint64_t rng = 12345;
    for (int i = 0; i < 300; i++) {
        memcpy(bad, snap, size);
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        size_t bit = (size_t)(rng % (size * 8));
        bad[bit / 8] ^= (uint8_t)(1u << (bit % 8));
        ENSURE_RESULT(hearth_world_snapshot_restore(w, bad, size), HEARTH_ERROR_INVALID_ARGUMENT);
    }
    memcpy(bad, snap, size);
    bad[8] = (uint8_t)(bad[8] + 1); /* another format version */
    ENSURE_RESULT(hearth_world_snapshot_restore(w, bad, size), HEARTH_ERROR_INVALID_ARGUMENT);
    {
        char msg[256];
        hearth_last_error_message(msg, sizeof msg);
        ENSURE(strstr(msg, "version") != NULL);
    }
    ENSURE(same_snapshot(w, after, after_size));

    free(bad);
    free(buf);
    free(after);
    free(snap);
    hearth_world_destroy(fresh);
    hearth_world_destroy(w);
    user_generators();
    return ensure_report("test_snapshot");
}
