// The multiblock writer: the blocks assembled in a vtkMultiBlockDataSet, each named (the names ParaView's
// pipeline browser and the readers show), and written by vtkXMLMultiBlockDataWriter, which puts each leaf
// block in its own .vtp or .vtu file under raystep/ and lists them in raystep.vtm.
#include "raystep/vtk_export/vtk_export.h"

#include <algorithm>
#include <filesystem>

#include <vtkCompositeDataSet.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLMultiBlockDataWriter.h>

#include "cell_set_block.h"
#include "geometry_block.h"
#include "raystep/record/events.h"
#include "raystep/util/error.h"
#include "walk_block.h"

namespace raystep::vtk_export {

namespace {

void add_block(vtkMultiBlockDataSet* parent, const std::string& name, vtkDataObject* block) {
  const unsigned int i = parent->GetNumberOfBlocks();
  parent->SetBlock(i, block);
  parent->GetMetaData(i)->Set(vtkCompositeDataSet::NAME(), name.c_str());
}

// A one-value string array in a dataset's field data: what the block is, for whoever opens the file alone.
void add_text(vtkDataObject* data, const char* name, const std::string& value) {
  auto a = vtkSmartPointer<vtkStringArray>::New();
  a->SetName(name);
  a->InsertNextValue(value);
  data->GetFieldData()->AddArray(a);
}

// The event codes of the "event" cell array, by name (index = code), as field data of a visited block.
void add_event_names(vtkDataObject* data) {
  auto a = vtkSmartPointer<vtkStringArray>::New();
  a->SetName("event_names");
  for (int code = 0; code < kEventTypeCount; ++code) a->InsertNextValue(event_type_name(EventType(code)));
  data->GetFieldData()->AddArray(a);
}

}  // namespace

ExportSummary write_vtk_export(const std::string& dir, const ExportInput& input) {
  ExportSummary summary;
  auto root = vtkSmartPointer<vtkMultiBlockDataSet>::New();

  auto geometry = geometry_polydata(*input.geometry);
  add_block(root, "geometry", geometry);
  summary.blocks.push_back("geometry");

  if (input.structure) {
    auto structure = cell_set_grid(input.structure->cells);
    add_text(structure, "structure", input.structure->kind);
    if (!input.structure->note.empty()) add_text(structure, "note", input.structure->note);
    add_block(root, "structure", structure);
    summary.blocks.push_back("structure");
    if (!input.structure->planes.empty()) {
      add_block(root, "planes", plane_polydata(input.structure->planes));
      summary.blocks.push_back("planes");
    }
  }

  if (input.trace) {
    for (size_t r = 0; r < input.trace->rays.size(); ++r) {
      RayWalk walk = ray_walk(*input.trace, r, input.trace_name);
      auto ray = vtkSmartPointer<vtkMultiBlockDataSet>::New();
      add_block(ray, "path", ray_path_polydata(input.trace->rays[r], walk.path, r));
      auto visited = cell_set_grid(walk.visited);
      add_event_names(visited);
      add_block(ray, "visited", visited);
      auto tests = ray_tests_polydata(walk.tests);
      add_event_names(tests);
      add_block(ray, "tests", tests);
      summary.tests.push_back(walk.tests.size());
      summary.visited.push_back(walk.visited.size());
      const std::string name = "ray " + std::to_string(r);
      add_block(root, name, ray);
      summary.blocks.push_back(name);
    }
  }

  const std::string vtm = (std::filesystem::path(dir) / kMultiBlockFile).string();
  auto writer = vtkSmartPointer<vtkXMLMultiBlockDataWriter>::New();
  writer->SetFileName(vtm.c_str());
  writer->SetInputData(root);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  if (writer->Write() != 1 || writer->GetErrorCode() != 0)
    throw InputError(dir, 0, "VTK could not write " + std::string(kMultiBlockFile));

  // What the writer made: the .vtm and the pieces in its folder.
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      summary.files.push_back(std::filesystem::relative(entry.path(), dir).string());
  std::sort(summary.files.begin(), summary.files.end());
  return summary;
}

}  // namespace raystep::vtk_export
