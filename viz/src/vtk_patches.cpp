// VTK adapter for Bézier patches: VTK_BEZIER_QUADRILATERAL cells, .vtu export, VTK's evaluation.
#include "casteljau/vtk_patches.h"
#include "error_internal.h"
#include "vtk_write.h"

#include <vtkBezierQuadrilateral.h>
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkHigherOrderQuadrilateral.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cassert>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

extern "C" int cj_vtk_quad_node(int m, int n, int i, int j) {
    const bool ib = i == 0 || i == m, jb = j == 0 || j == n;
    if (ib && jb) { // corners (0,0), (m,0), (m,n), (0,n)
        if (j == 0) return i == 0 ? 0 : 1;
        return i == 0 ? 3 : 2;
    }
    const int eu = m - 1, ev = n - 1; // interior points per edge
    if (jb)                           // bottom (j = 0) or top (j = n) edge, i = 1..m-1
        return 4 + (j == 0 ? 0 : eu + ev) + (i - 1);
    if (ib) // right (i = m) or left (i = 0) edge, j = 1..n-1
        return 4 + (i == m ? eu : 2 * eu + ev) + (j - 1);
    return 4 + 2 * (eu + ev) + (j - 1) * eu + (i - 1);
}

extern "C" cj_status cj_vtk_quad_node_check(int m, int n) {
    const int order[2] = {m, n};
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const int theirs = vtkHigherOrderQuadrilateral::PointIndexFromIJK(i, j, order);
            const int ours = cj_vtk_quad_node(m, n, i, j);
            if (theirs != ours)
                return cj_fail(CJ_ERR_UNSUPPORTED,
                               "degree (%d,%d), control point (%d,%d): our VTK node %d, VTK's %d",
                               m, n, i, j, ours, theirs);
        }
    return CJ_OK;
}

namespace {

cj_status check_patch(const cj_patch &p, size_t index) {
    cj_status st = cj_patch_check(&p);
    if (st) return cj_fail(st, "patch %zu: %s", index, cj_last_error());
    if (p.deg_u < 1 || p.deg_v < 1)
        return cj_fail(CJ_ERR_DEGREE,
                       "patch %zu: a VTK Bezier quadrilateral needs degrees >= 1, got (%d,%d)",
                       index, p.deg_u, p.deg_v);
    return CJ_OK;
}

vtkSmartPointer<vtkUnstructuredGrid> build_grid(const cj_patch *patches, size_t count) {
    bool rational = false;
    for (size_t q = 0; q < count; ++q) rational = rational || patches[q].weights != nullptr;
    auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkIntArray> degrees;
    degrees->SetName("HigherOrderDegrees");
    degrees->SetNumberOfComponents(3);
    vtkNew<vtkDoubleArray> weights;
    weights->SetName("RationalWeights");
    weights->SetNumberOfComponents(1);
    grid->Allocate(static_cast<vtkIdType>(count));
    std::vector<vtkIdType> ids;
    for (size_t q = 0; q < count; ++q) {
        const cj_patch &p = patches[q];
        const int m = p.deg_u, n = p.deg_v, np = (m + 1) * (n + 1);
        const vtkIdType base = points->GetNumberOfPoints();
        points->SetNumberOfPoints(base + np);
        if (rational) weights->SetNumberOfTuples(base + np);
        ids.assign(static_cast<size_t>(np), 0);
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= m; ++i) {
                const int ours = j * (m + 1) + i, node = cj_vtk_quad_node(m, n, i, j);
                const vtkIdType id = base + node;
                points->SetPoint(id, p.pts + 3 * ours);
                if (rational) weights->SetValue(id, p.weights ? p.weights[ours] : 1.0);
                ids[static_cast<size_t>(node)] = id;
            }
        grid->InsertNextCell(VTK_BEZIER_QUADRILATERAL, np, ids.data());
        const int deg[3] = {m, n, 0};
        degrees->InsertNextTypedTuple(deg);
    }
    grid->SetPoints(points);
    grid->GetCellData()->SetHigherOrderDegrees(degrees);
    if (rational) grid->GetPointData()->SetRationalWeights(weights);
    return grid;
}

} // namespace

extern "C" cj_status cj_vtk_write_patches(const char *path, const cj_patch *patches, size_t count) {
    assert(path != nullptr);
    if (count == 0) return cj_fail(CJ_ERR_EMPTY, "no patches to write to %s", path);
    assert(patches != nullptr);
    for (size_t q = 0; q < count; ++q) {
        cj_status st = check_patch(patches[q], q);
        if (st) return st;
    }
    vtkSmartPointer<vtkUnstructuredGrid> grid = build_grid(patches, count);
    return cj_vtk_write_grid(grid, path);
}

extern "C" cj_status cj_vtk_read_patch_count(const char *path, size_t *ncells, int degrees[2]) {
    assert(path != nullptr && ncells != nullptr);
    if (std::FILE *f = std::fopen(path, "rb"))
        std::fclose(f);
    else
        return cj_fail(CJ_ERR_IO, "cannot open %s", path);
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(path);
    reader->Update();
    vtkUnstructuredGrid *grid = reader->GetOutput();
    if (!grid || grid->GetNumberOfCells() == 0)
        return cj_fail(CJ_ERR_IO, "%s holds no cells VTK can read", path);
    *ncells = static_cast<size_t>(grid->GetNumberOfCells());
    if (degrees) {
        vtkDataArray *d = grid->GetCellData()->GetHigherOrderDegrees();
        if (!d) d = grid->GetCellData()->GetArray("HigherOrderDegrees");
        if (!d) return cj_fail(CJ_ERR_IO, "%s has no HigherOrderDegrees", path);
        degrees[0] = static_cast<int>(d->GetComponent(0, 0));
        degrees[1] = static_cast<int>(d->GetComponent(0, 1));
    }
    return CJ_OK;
}

extern "C" cj_status cj_vtk_eval_patch(const cj_patch *p, const double *uv, size_t n,
                                       double *out3) {
    assert(p != nullptr && (uv != nullptr || n == 0) && (out3 != nullptr || n == 0));
    cj_status st = check_patch(*p, 0);
    if (st) return st;
    for (size_t k = 0; k < 2 * n; ++k) {
        if (!std::isfinite(uv[k]))
            return cj_fail(CJ_ERR_NONFINITE, "parameter pair %zu is not finite", k / 2);
        if (uv[k] < 0.0 || uv[k] > 1.0)
            return cj_fail(CJ_ERR_RANGE, "parameter pair %zu: %c = %.17g is outside [0,1]", k / 2,
                           k % 2 ? 'v' : 'u', uv[k]);
    }
    vtkSmartPointer<vtkUnstructuredGrid> grid = build_grid(p, 1);
    vtkBezierQuadrilateral *cell = vtkBezierQuadrilateral::SafeDownCast(grid->GetCell(0));
    if (!cell) return cj_fail(CJ_ERR_UNSUPPORTED, "VTK did not build a Bezier quadrilateral");
    const vtkIdType npts = cell->GetNumberOfPoints();
    cell->SetRationalWeightsFromPointData(grid->GetPointData(), npts);
    std::vector<double> w(static_cast<size_t>(npts));
    for (size_t k = 0; k < n; ++k) {
        double pc[3] = {uv[2 * k], uv[2 * k + 1], 0.0};
        int sub = 0;
        cell->EvaluateLocation(sub, pc, out3 + 3 * k, w.data());
    }
    return CJ_OK;
}
