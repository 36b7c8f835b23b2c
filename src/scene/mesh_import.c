/* mesh_import.c — assimp on bytes in memory (sh__mesh_import,
 * mesh_internal.h): the one file that uses assimp's API.
 *
 * assimp's contract (include/assimp/cimport.h, cfileio.h): aiImportFileEx
 * reads the named file through the given aiFileIO and returns a read-only
 * scene owned until aiReleaseImport, or NULL with a message in
 * aiGetErrorString(); aiApplyPostProcessing runs further steps on it (and
 * releases it itself when a step fails).  Our aiFileIO serves the main file
 * from memory — the bytes the guard checked — and every other file the
 * importer asks for (an OBJ's material library) either not at all or through
 * sh_input_open's policy (regular files only, size checked first).
 *
 * The steps are the ones sh_mesh_load always used (Triangulate,
 * JoinIdenticalVertices, PreTransformVertices, SortByPType,
 * ValidateDataStructure), split in two: the import with validation, then the
 * others — as Importer::ReadFile itself runs them (validation first,
 * ScenePreprocessor, the rest), so the result is the same — with the raw
 * positions checked in between, before a step could merge a NaN away. */
#include "scene/mesh_internal.h"

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Largest other file (material library, ...) the importer may read. */
#define SIDE_FILE_MAX_BYTES (256LL << 20)

int sh__mesh_import_knows_ext(const char *ext)
{
    char buf[64];
    if (!ext || strlen(ext) > sizeof buf - 3) return 0;
    snprintf(buf, sizeof buf, "*.%s", ext);
    return aiIsExtensionSupported(buf) == AI_TRUE;
}

/* ------------------------------------------------------------- files */

typedef struct {
    const unsigned char *main;
    size_t main_size;
    const char *main_name;
    int side_files;
} fio_ctx;

typedef struct {
    const unsigned char *data;
    size_t size, pos;
    char *owned; /* a side file's bytes */
} memfile;

/* aiFile over bytes in memory, as assimp's MemoryIOStream: Read gives whole
 * elements only, Seek refuses a position past the end, Write writes nothing. */
static size_t f_read(struct aiFile *f, char *buf, size_t size, size_t count)
{
    memfile *m = (memfile *)f->UserData;
    if (size == 0 || count == 0) return 0;
    size_t cnt = (m->size - m->pos) / size;
    if (cnt > count) cnt = count;
    memcpy(buf, m->data + m->pos, cnt * size);
    m->pos += cnt * size;
    return cnt;
}
static size_t f_write(struct aiFile *f, const char *buf, size_t size, size_t count) { return 0; }
static size_t f_tell(struct aiFile *f) { return ((memfile *)f->UserData)->pos; }
static size_t f_size(struct aiFile *f) { return ((memfile *)f->UserData)->size; }
static void f_flush(struct aiFile *f) {}
static enum aiReturn f_seek(struct aiFile *f, size_t off, enum aiOrigin origin)
{
    memfile *m = (memfile *)f->UserData;
    size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? m->pos : m->size;
    if (origin != aiOrigin_SET && origin != aiOrigin_CUR && origin != aiOrigin_END) return aiReturn_FAILURE;
    if (off > m->size - base) return aiReturn_FAILURE;
    m->pos = base + off;
    return aiReturn_SUCCESS;
}

/* Open for reading only: the main file by its exact name from memory, any
 * other through sh_input_read_all when side files are allowed, else none
 * (assimp then goes without, e.g. an OBJ without its materials). */
static struct aiFile *fio_open(struct aiFileIO *io, const char *name, const char *mode)
{
    const fio_ctx *c = (const fio_ctx *)io->UserData;
    if (!name || (mode && (strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+')))) return NULL;
    memfile *m = calloc(1, sizeof *m);
    struct aiFile *f = calloc(1, sizeof *f);
    if (!m || !f) goto fail;
    if (!strcmp(name, c->main_name)) {
        m->data = c->main;
        m->size = c->main_size;
    } else if (c->side_files) {
        size_t n;
        if (sh_input_read_all("mesh's side file", name, SIDE_FILE_MAX_BYTES, &m->owned, &n)) goto fail;
        m->data = (const unsigned char *)m->owned;
        m->size = n;
    } else {
        goto fail;
    }
    f->ReadProc = f_read;
    f->WriteProc = f_write;
    f->TellProc = f_tell;
    f->FileSizeProc = f_size;
    f->SeekProc = f_seek;
    f->FlushProc = f_flush;
    f->UserData = (aiUserData)m;
    return f;
fail:
    free(m);
    free(f);
    return NULL;
}

/* Close a file of fio_open. */
static void fio_close(struct aiFileIO *io, struct aiFile *f)
{
    if (!f) return;
    memfile *m = (memfile *)f->UserData;
    if (m) free(m->owned);
    free(m);
    free(f);
}

/* ------------------------------------------------------------- import */

/* Raw positions (and normals, when used) finite and in range. */
static int check_raw(const struct aiScene *sc, int flags)
{
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            const float p[3] = {am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z};
            for (int k = 0; k < 3; k++)
                if (!isfinite(p[k]))
                    return sh_error(SH_EFORMAT, "vertex %u of submesh %u has a non-finite coordinate (%g)", v, i, p[k]);
                else if (fabs(p[k]) > SH_MESH_MAX_COORD)
                    return sh_error(SH_EFORMAT, "vertex %u of submesh %u has a coordinate out of range: %g (|x| <= %g)",
                                    v, i, p[k], SH_MESH_MAX_COORD);
            if (am->mNormals && !(flags & SH_MESH_COMPUTE_NORMALS)) {
                const float n[3] = {am->mNormals[v].x, am->mNormals[v].y, am->mNormals[v].z};
                for (int k = 0; k < 3; k++)
                    if (!isfinite(n[k])) return sh_error(SH_EFORMAT, "vertex %u of submesh %u has a non-finite normal", v, i);
            }
        }
    }
    return SH_OK;
}

/* Copy the triangles out: submeshes concatenated, points and lines skipped. */
static int copy_out(const struct aiScene *sc, int flags, sh_mesh *out, sh_mesh_report *rep)
{
    long long nv = 0, nt = 0;
    int have_normals = 1;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        int tris = 0;
        for (unsigned k = 0; k < am->mNumFaces; k++) {
            if (am->mFaces[k].mNumIndices == 3) tris++;
            else rep->skipped_primitives++;
        }
        if (tris == 0) continue;
        rep->submeshes++;
        nv += am->mNumVertices;
        nt += tris;
        if (!am->mNormals) have_normals = 0;
    }
    if (nv > SH_MESH_MAX_ELEMS || nt > SH_MESH_MAX_ELEMS)
        return sh_error(SH_EFORMAT, "%lld vertices and %lld triangles exceed the limit %d", nv, nt, SH_MESH_MAX_ELEMS);
    if (nt == 0) return sh_error(SH_EFORMAT, "no triangles");
    const int with_normals = have_normals && !(flags & SH_MESH_COMPUTE_NORMALS);
    out->pos = malloc(sizeof(double) * 3 * (size_t)nv);
    out->normal = with_normals ? malloc(sizeof(double) * 3 * (size_t)nv) : NULL;
    out->tri = malloc(sizeof(int) * 3 * (size_t)nt);
    if (!out->pos || !out->tri || (with_normals && !out->normal)) {
        sh_mesh_free(out);
        return sh_error(SH_ENOMEM, "out of memory copying a mesh of %lld vertices", nv);
    }
    int vbase = 0, t = 0;
    for (unsigned i = 0; i < sc->mNumMeshes; i++) {
        const struct aiMesh *am = sc->mMeshes[i];
        int tris = 0;
        for (unsigned k = 0; k < am->mNumFaces; k++) tris += am->mFaces[k].mNumIndices == 3;
        if (tris == 0) continue;
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            double *p = out->pos + 3 * (size_t)(vbase + (int)v);
            p[0] = am->mVertices[v].x;
            p[1] = am->mVertices[v].y;
            p[2] = am->mVertices[v].z;
            if (out->normal) {
                double *n = out->normal + 3 * (size_t)(vbase + (int)v);
                n[0] = am->mNormals[v].x;
                n[1] = am->mNormals[v].y;
                n[2] = am->mNormals[v].z;
            }
        }
        for (unsigned k = 0; k < am->mNumFaces; k++) {
            const struct aiFace *fc = &am->mFaces[k];
            if (fc->mNumIndices != 3) continue;
            for (int j = 0; j < 3; j++) out->tri[3 * t + j] = vbase + (int)fc->mIndices[j];
            t++;
        }
        vbase += (int)am->mNumVertices;
    }
    out->nvert = (int)nv;
    out->ntri = (int)nt;
    return SH_OK;
}

int sh__mesh_import(const unsigned char *bytes, size_t size, const char *name, int side_files, int flags,
                    sh_mesh *m, sh_mesh_report *rep)
{
    memset(m, 0, sizeof *m);
    rep->submeshes = rep->skipped_primitives = 0;
    fio_ctx ctx = {bytes, size, name, side_files};
    struct aiFileIO io = {fio_open, fio_close, (aiUserData)&ctx};
    const struct aiScene *sc = aiImportFileEx(name, aiProcess_ValidateDataStructure, &io);
    if (!sc) {
        const char *why = aiGetErrorString();
        return sh_error(SH_EFORMAT, "%s", (why && *why) ? why : "assimp failed");
    }
    int st = check_raw(sc, flags);
    if (st) {
        aiReleaseImport(sc);
        return st;
    }
    sc = aiApplyPostProcessing(sc, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                       aiProcess_PreTransformVertices | aiProcess_SortByPType);
    if (!sc) return sh_error(SH_EFORMAT, "assimp's post-processing failed");
    st = copy_out(sc, flags, m, rep);
    aiReleaseImport(sc);
    return st;
}
