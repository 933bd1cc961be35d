/* The tessellate command's .vtu output: a VTK XML UnstructuredGrid of triangles (cell type 5),
 * ASCII, with the normals and (u,v) as point data and the patch index as cell data. Written
 * here rather than through VTK so that the tool does not load VTK's libraries. */
#include "mesh_vtu.h"

#include "file_internal.h"

#include <inttypes.h>
#include <stdio.h>

static void put_array(FILE *f, const char *type, const char *name, int comps, const double *v,
                      size_t n) {
    fprintf(f,
            "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" "
            "format=\"ascii\">\n",
            type, name, comps);
    for (size_t i = 0; i < n; ++i) {
        fprintf(f, "          ");
        for (int k = 0; k < comps; ++k)
            fprintf(f, "%s%.17g", k ? " " : "", v[i * (size_t)comps + (size_t)k]);
        fputc('\n', f);
    }
    fprintf(f, "        </DataArray>\n");
}

int mesh_write_vtu(const cj_mesh *m, const char *path, char *why, size_t why_size) {
    cj_atomic_file out;
    if (cj_atomic_open(&out, path)) {
        snprintf(why, why_size, "%s", cj_last_error());
        return -1;
    }
    FILE *f = out.fp;
    fprintf(f,
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <UnstructuredGrid>\n"
            "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n"
            "      <Points>\n",
            m->vertex_count, m->triangle_count);
    put_array(f, "Float64", "Points", 3, m->positions, m->vertex_count);
    fprintf(f, "      </Points>\n      <PointData Normals=\"Normals\" TCoords=\"UV\">\n");
    put_array(f, "Float64", "Normals", 3, m->normals, m->vertex_count);
    put_array(f, "Float64", "UV", 2, m->uvs, m->vertex_count);
    fprintf(f, "      </PointData>\n      <CellData Scalars=\"patch\">\n"
               "        <DataArray type=\"Int32\" Name=\"patch\" format=\"ascii\">\n");
    for (size_t t = 0; t < m->triangle_count; ++t)
        fprintf(f, "          %" PRId32 "\n", m->triangle_patch[t]);
    fprintf(f, "        </DataArray>\n      </CellData>\n      <Cells>\n"
               "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for (size_t t = 0; t < m->triangle_count; ++t) {
        const uint32_t *v = m->triangles + 3 * t;
        fprintf(f, "          %" PRIu32 " %" PRIu32 " %" PRIu32 "\n", v[0], v[1], v[2]);
    }
    fprintf(f, "        </DataArray>\n"
               "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for (size_t t = 0; t < m->triangle_count; ++t) fprintf(f, "          %zu\n", 3 * (t + 1));
    fprintf(f, "        </DataArray>\n"
               "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (size_t t = 0; t < m->triangle_count; ++t) fprintf(f, "          5\n");
    fprintf(f, "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n"
               "</VTKFile>\n");
    if (cj_atomic_commit(&out)) {
        snprintf(why, why_size, "%s", cj_last_error());
        return -1;
    }
    return 0;
}
