/* fuzz_mesh.c — mesh files through the guard, and what passes it through
 * assimp, in this process (src/scene/mesh_internal.h).
 *
 * sh_mesh_load runs the importer in a forked child (mesh_sandbox.c); a
 * fork per input would make fuzzing slow, and a crash in the child would be
 * the designed outcome, not a finding.  So the harness calls the parts the
 * child and the parent run, directly:
 *  - the guard (sh__mesh_guard) on the bytes, named fuzz.ply when they start
 *    with "ply" (any case), else fuzz.obj: a refusal must be SH_EFORMAT (or
 *    SH_ENOMEM) with one line of reason and nothing allocated;
 *  - on what it accepts, assimp in-process (sh__mesh_import, no other file
 *    readable) — every accepted PLY input, and one accepted OBJ input in 8
 *    (chosen by a hash of its bytes, so a reproducer reproduces): assimp's
 *    OBJ reader fills a 16 MB line buffer for every file, some 20 ms under
 *    ASan, which would make the harness 5 times slower —
 *    it must neither crash, hang (libFuzzer's -timeout) nor leak
 *    (LeakSanitizer), and a mesh must stay within the guard's bounds — the
 *    bounds the parent holds the child to — with finite coordinates within
 *    SH_MESH_MAX_COORD and indices in range; then sh_mesh_check on it;
 *  - bytes that start with the frame magic "SHMESH\1\n" go instead to the
 *    parent's frame reader (sh__mesh_frame_*), fed in chunks of 1 to 7
 *    bytes, with bounds of 64 vertices and triangles: a complete frame must
 *    hold what its header says within the bounds, anything else a reason.
 * Coverage feedback comes from shlab's code only (assimp is not built with
 * instrumentation): the guard's readers, the number reader, the copy-out,
 * sh_mesh_check and the frame reader; assimp runs as an oracle of the
 * guard — an input that passes the guard and still breaks assimp is a gap. */
#include "fuzz.h"

#include <ctype.h>
#include <math.h>

#include "scene/mesh_internal.h"

static void fuzz_frame(const uint8_t *d, size_t n)
{
    sh_mesh_frame_reader r;
    sh__mesh_frame_begin(&r, 64, 64);
    size_t i = 0, k = 1;
    int bad = 0;
    while (i < n && !bad) {
        const size_t c = k < n - i ? k : n - i;
        bad = sh__mesh_frame_feed(&r, d + i, c) != 0;
        i += c;
        k = k % 7 + 1;
    }
    const int complete = !bad && sh__mesh_frame_complete(&r);
    if (!complete) {
        FUZZ_CHECK(r.why[0], "a broken frame without a reason");
    } else if (r.hdr.kind == SH_FRAME_MESH) {
        FUZZ_CHECK(r.mesh.nvert >= 1 && r.mesh.nvert <= 64 && r.mesh.ntri >= 1 && r.mesh.ntri <= 64,
                   "%d vertices, %d triangles past the bounds", r.mesh.nvert, r.mesh.ntri);
        double s = 0;
        for (int v = 0; v < 3 * r.mesh.nvert; v++) s += r.mesh.pos[v] + (r.mesh.normal ? r.mesh.normal[v] : 0);
        for (int t = 0; t < 3 * r.mesh.ntri; t++) s += r.mesh.tri[t];
        (void)s;
    } else {
        FUZZ_CHECK(r.hdr.kind == SH_FRAME_ERROR && r.msg[0] && strlen(r.msg) == r.hdr.msglen, "a bad error frame");
    }
    sh__mesh_frame_end(&r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size >= 8 && !memcmp(data, "SHMESH\1\n", 8)) {
        fuzz_frame(data, size);
        return 0;
    }
    const int ply = size >= 3 && tolower(data[0]) == 'p' && tolower(data[1]) == 'l' && tolower(data[2]) == 'y';
    sh_mesh_guard g;
    int st = sh__mesh_guard(data, size, ply ? "fuzz.ply" : "fuzz.obj", 0, &g);
    if (st) {
        FUZZ_CHECK(st == SH_EFORMAT || st == SH_ENOMEM, "guard status %d", st);
        FUZZ_CHECK(!g.canon && !g.name, "guard left memory after an error");
        fuzz_check_reason();
        return 0;
    }
    FUZZ_CHECK(g.format == (ply ? SH_MESH_FMT_PLY : SH_MESH_FMT_OBJ), "format %d", g.format);
    FUZZ_CHECK(g.max_triangles >= 0 && g.max_triangles <= SH_MESH_MAX_ELEMS, "bound %lld", g.max_triangles);
    uint32_t h = 2166136261u; /* FNV-1a */
    for (size_t i = 0; i < size; i++) h = (h ^ data[i]) * 16777619u;
    if (!ply && (h & 7)) {
        sh__mesh_guard_free(&g);
        return 0;
    }
    sh_mesh m;
    sh_mesh_report rep;
    memset(&rep, 0, sizeof rep);
    st = sh__mesh_import(g.bytes, g.size, g.name, 0, 0, &m, &rep);
    if (st == SH_OK) {
        FUZZ_CHECK(m.nvert >= 1 && m.nvert <= g.max_vertices, "%d vertices, the guard's bound %lld", m.nvert,
                   g.max_vertices);
        FUZZ_CHECK(m.ntri >= 1 && m.ntri <= g.max_triangles, "%d triangles, the guard's bound %lld", m.ntri,
                   g.max_triangles);
        for (int v = 0; v < 3 * m.nvert; v++)
            FUZZ_CHECK(fabs(m.pos[v]) <= SH_MESH_MAX_COORD, "coordinate %g passed the guard", m.pos[v]);
        for (int t = 0; t < 3 * m.ntri; t++) FUZZ_CHECK(m.tri[t] >= 0 && m.tri[t] < m.nvert, "index %d", m.tri[t]);
        st = sh_mesh_check(&m, SH_MESH_ALLOW_NONMANIFOLD, &rep);
        if (st) {
            FUZZ_CHECK(st == SH_EFORMAT || st == SH_ENOMEM, "check status %d", st);
            fuzz_check_reason();
        }
        sh_mesh_free(&m);
    } else {
        FUZZ_CHECK(st == SH_EFORMAT || st == SH_ENOMEM, "import status %d", st);
        FUZZ_CHECK(!m.pos && !m.tri && !m.normal, "mesh left after an error");
        fuzz_check_reason();
    }
    sh__mesh_guard_free(&g);
    return 0;
}
