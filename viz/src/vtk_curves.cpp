// VTK adapter for curves: Bézier curves as VTK_BEZIER_CURVE cells (write, read back, evaluate
// with VTK's own cell code) and VTK's Kochanek spline. See casteljau/vtk_export.h.
// (Surface patches as VTK_BEZIER_QUADRILATERAL cells belong in a sibling file.)
#include "casteljau/vtk_export.h"
#include "error_internal.h"
#include "vtk_write.h"

#include <vtkBezierCurve.h>
#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkKochanekSpline.h>
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

namespace {

// One curve as the builder sees it: weights == nullptr for a polynomial curve.
struct curve_in {
    int degree;
    int dim;
    const double *pts;
    const double *weights;
};

cj_status check_curve(const curve_in &c, size_t index) {
    if (c.dim > 3)
        return cj_fail(CJ_ERR_DIMENSION, "curve %zu: dimension %d does not fit VTK's 3D points",
                       index, c.dim);
    if (c.degree < 1)
        return cj_fail(CJ_ERR_DEGREE, "curve %zu: a VTK Bezier curve needs degree >= 1, got %d",
                       index, c.degree);
    return CJ_OK;
}

// VTK node order: b_0, b_n, b_1, ..., b_{n-1}. Returns our index of VTK node k.
int ours_of_vtk(int k, int n) {
    if (k == 0) return 0;
    if (k == 1) return n;
    return k - 1;
}

vtkSmartPointer<vtkUnstructuredGrid> build_grid(const std::vector<curve_in> &curves) {
    bool rational = false;
    for (const curve_in &c : curves) rational = rational || c.weights != nullptr;
    auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkIntArray> degrees;
    degrees->SetName("HigherOrderDegrees");
    degrees->SetNumberOfComponents(3);
    vtkNew<vtkDoubleArray> weights;
    weights->SetName("RationalWeights");
    weights->SetNumberOfComponents(1);
    grid->Allocate(static_cast<vtkIdType>(curves.size()));
    std::vector<vtkIdType> ids;
    for (const curve_in &c : curves) {
        const int n = c.degree;
        ids.assign(static_cast<size_t>(n) + 1, 0);
        for (int k = 0; k <= n; ++k) {
            const int i = ours_of_vtk(k, n);
            double p[3] = {0.0, 0.0, 0.0};
            for (int q = 0; q < c.dim; ++q) p[q] = c.pts[i * c.dim + q];
            ids[static_cast<size_t>(k)] = points->InsertNextPoint(p);
            if (rational) weights->InsertNextValue(c.weights ? c.weights[i] : 1.0);
        }
        grid->InsertNextCell(VTK_BEZIER_CURVE, n + 1, ids.data());
        const int deg[3] = {n, 0, 0};
        degrees->InsertNextTypedTuple(deg);
    }
    grid->SetPoints(points);
    grid->GetCellData()->SetHigherOrderDegrees(degrees);
    if (rational) grid->GetPointData()->SetRationalWeights(weights);
    return grid;
}

cj_status eval_cell(vtkUnstructuredGrid *grid, vtkIdType cell_id, const double *ts, size_t nt,
                    double *out3) {
    for (size_t j = 0; j < nt; ++j) {
        if (!std::isfinite(ts[j]))
            return cj_fail(CJ_ERR_NONFINITE, "parameter %zu is not finite", j);
        if (ts[j] < 0.0 || ts[j] > 1.0)
            return cj_fail(CJ_ERR_RANGE, "parameter %zu = %.17g is outside [0,1]", j, ts[j]);
    }
    vtkCell *cell = grid->GetCell(cell_id);
    vtkBezierCurve *bc = vtkBezierCurve::SafeDownCast(cell);
    if (!bc)
        return cj_fail(CJ_ERR_UNSUPPORTED, "cell %lld is not a VTK Bezier curve",
                       static_cast<long long>(cell_id));
    const vtkIdType npts = bc->GetNumberOfPoints();
    bc->SetRationalWeightsFromPointData(grid->GetPointData(), npts);
    std::vector<double> w(static_cast<size_t>(npts));
    for (size_t j = 0; j < nt; ++j) {
        double pc[3] = {ts[j], 0.0, 0.0};
        int sub = 0;
        bc->EvaluateLocation(sub, pc, out3 + 3 * j, w.data());
    }
    return CJ_OK;
}

} // namespace

extern "C" cj_status cj_vtk_write_curves(const char *path, const cj_bezier *curves, size_t ncurves,
                                         const cj_rbezier *rcurves, size_t nrcurves) {
    assert(path != nullptr);
    if (ncurves + nrcurves == 0) return cj_fail(CJ_ERR_EMPTY, "no curves to write to %s", path);
    std::vector<curve_in> in;
    for (size_t i = 0; i < ncurves; ++i) {
        cj_status st = cj_bezier_check(&curves[i], CJ_BEZIER_MAX_DEGREE);
        if (st) return st;
        in.push_back({curves[i].degree, curves[i].dim, curves[i].pts, nullptr});
        if ((st = check_curve(in.back(), i))) return st;
    }
    for (size_t i = 0; i < nrcurves; ++i) {
        cj_status st = cj_rbezier_check(&rcurves[i]);
        if (st) return st;
        in.push_back({rcurves[i].degree, rcurves[i].dim, rcurves[i].pts, rcurves[i].weights});
        if ((st = check_curve(in.back(), ncurves + i))) return st;
    }
    vtkSmartPointer<vtkUnstructuredGrid> grid = build_grid(in);
    return cj_vtk_write_grid(grid, path);
}

extern "C" cj_status cj_vtk_read_curves(const char *path, int *degrees, size_t cap_cells,
                                        double *pts3, double *weights, size_t cap_pts,
                                        size_t *ncells, size_t *npts, int *rational) {
    assert(path && ncells && npts);
    std::FILE *f = std::fopen(path, "rb");
    if (!f) return cj_fail(CJ_ERR_IO, "cannot open %s", path);
    std::fclose(f);
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    if (!reader->CanReadFile(path))
        return cj_fail(CJ_ERR_IO, "%s is not a VTK unstructured grid file", path);
    reader->SetFileName(path);
    reader->Update();
    vtkUnstructuredGrid *grid = reader->GetOutput();
    if (!grid || !grid->GetPoints()) return cj_fail(CJ_ERR_IO, "VTK could not read %s", path);
    const vtkIdType nc = grid->GetNumberOfCells();
    size_t total = 0;
    for (vtkIdType c = 0; c < nc; ++c) {
        if (grid->GetCellType(c) != VTK_BEZIER_CURVE)
            return cj_fail(CJ_ERR_UNSUPPORTED, "%s: cell %lld has VTK type %d, not a Bezier curve",
                           path, static_cast<long long>(c), grid->GetCellType(c));
        vtkNew<vtkIdList> ids;
        grid->GetCellPoints(c, ids);
        total += static_cast<size_t>(ids->GetNumberOfIds());
    }
    vtkDataArray *w = grid->GetPointData()->GetArray("RationalWeights");
    *ncells = static_cast<size_t>(nc);
    *npts = total;
    if (rational) *rational = w != nullptr;
    if (cap_cells < static_cast<size_t>(nc) || cap_pts < total)
        return cj_fail(CJ_ERR_BUFFER, "%s holds %lld cells and %zu points; buffers hold %zu, %zu",
                       path, static_cast<long long>(nc), total, cap_cells, cap_pts);
    size_t at = 0;
    for (vtkIdType c = 0; c < nc; ++c) {
        vtkNew<vtkIdList> ids;
        grid->GetCellPoints(c, ids);
        const int n = static_cast<int>(ids->GetNumberOfIds()) - 1;
        degrees[c] = n;
        for (int k = 0; k <= n; ++k) {
            const size_t i = at + static_cast<size_t>(ours_of_vtk(k, n));
            const vtkIdType id = ids->GetId(k);
            grid->GetPoint(id, pts3 + 3 * i);
            if (weights) weights[i] = w ? w->GetTuple1(id) : 1.0;
        }
        at += static_cast<size_t>(n) + 1;
    }
    return CJ_OK;
}

extern "C" cj_status cj_vtk_eval_bezier(const cj_bezier *c, const double *ts, size_t nt,
                                        double *out3) {
    assert(c && (nt == 0 || (ts && out3)));
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    std::vector<curve_in> in{{c->degree, c->dim, c->pts, nullptr}};
    if ((st = check_curve(in[0], 0))) return st;
    vtkSmartPointer<vtkUnstructuredGrid> grid = build_grid(in);
    return eval_cell(grid, 0, ts, nt, out3);
}

extern "C" cj_status cj_vtk_eval_rbezier(const cj_rbezier *c, const double *ts, size_t nt,
                                         double *out3) {
    assert(c && (nt == 0 || (ts && out3)));
    cj_status st = cj_rbezier_check(c);
    if (st) return st;
    std::vector<curve_in> in{{c->degree, c->dim, c->pts, c->weights}};
    if ((st = check_curve(in[0], 0))) return st;
    vtkSmartPointer<vtkUnstructuredGrid> grid = build_grid(in);
    return eval_cell(grid, 0, ts, nt, out3);
}

extern "C" cj_status cj_vtk_kochanek_eval(const double *pts, size_t npts, int dim, double tension,
                                          double continuity, double bias, int closed,
                                          const double *ts, size_t nt, double *out) {
    assert(pts && (nt == 0 || (ts && out)));
    if (dim < 1 || dim > 3) return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..3", dim);
    if (npts < 2 || (closed && npts < 3))
        return cj_fail(CJ_ERR_EMPTY, "a %s spline needs at least %d points, got %zu",
                       closed ? "closed" : "open", closed ? 3 : 2, npts);
    cj_status st = cj_check_points(pts, npts, dim, "spline point");
    if (st) return st;
    if (!std::isfinite(tension) || !std::isfinite(continuity) || !std::isfinite(bias))
        return cj_fail(CJ_ERR_NONFINITE, "Kochanek tension, continuity or bias is not finite");
    const double tmax = static_cast<double>(npts - 1) + (closed ? 1.0 : 0.0);
    for (size_t j = 0; j < nt; ++j)
        if (!std::isfinite(ts[j]) || ts[j] < 0.0 || ts[j] > tmax)
            return cj_fail(CJ_ERR_RANGE, "parameter %zu = %.17g is outside [0, %g]", j, ts[j],
                           tmax);
    const double kap = 0.5 * (1.0 - tension);
    const size_t d = static_cast<size_t>(dim);
    for (size_t q = 0; q < d; ++q) {
        vtkNew<vtkKochanekSpline> s;
        s->SetDefaultTension(tension);
        s->SetDefaultContinuity(continuity);
        s->SetDefaultBias(bias);
        for (size_t j = 0; j < npts; ++j) s->AddPoint(static_cast<double>(j), pts[j * d + q]);
        if (closed) {
            s->ClosedOn();
        } else {
            s->SetLeftConstraint(1);
            s->SetLeftValue(kap * (pts[d + q] - pts[q]));
            s->SetRightConstraint(1);
            s->SetRightValue(kap * (pts[(npts - 1) * d + q] - pts[(npts - 2) * d + q]));
        }
        s->Compute();
        for (size_t j = 0; j < nt; ++j) out[j * d + q] = s->Evaluate(ts[j]);
    }
    return CJ_OK;
}
