// The one way viz/ writes a VTK XML file: to a temporary next to it, renamed when complete.
#include "vtk_write.h"

#include "error_internal.h"

#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtkXMLWriter.h>

#include <cstdio>
#include <string>

cj_status cj_vtk_write_xml(vtkXMLWriter *writer, vtkDataObject *data, const char *path) {
    const std::string tmp = std::string(path) + ".tmp";
    // Probe the location first so that an unwritable path fails with our message alone
    // (VTK would print its own error to the console).
    if (std::FILE *probe = std::fopen(tmp.c_str(), "wb"))
        std::fclose(probe);
    else
        return cj_fail(CJ_ERR_IO, "cannot create %s", tmp.c_str());
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    writer->SetCompressorTypeToNone();
    if (writer->Write() != 1) {
        std::remove(tmp.c_str());
        return cj_fail(CJ_ERR_IO, "VTK could not write %s", tmp.c_str());
    }
    if (std::rename(tmp.c_str(), path) != 0) {
        std::remove(tmp.c_str());
        return cj_fail(CJ_ERR_IO, "could not rename %s to %s", tmp.c_str(), path);
    }
    return CJ_OK;
}

cj_status cj_vtk_write_grid(vtkUnstructuredGrid *grid, const char *path) {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    return cj_vtk_write_xml(writer, grid, path);
}
