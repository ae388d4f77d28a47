#pragma once

#include <vtkNew.h>

#include "boneless/TriMesh.h"
#include "boneless/ui/MeshView.h"

class vtkActor;
class vtkPolyData;
class vtkPolyDataMapper;

namespace boneless::ui {

class Document;

// The take's floor: the lowest marker height over every frame (placed with the document's
// display alignment), the grid wide enough for every place the markers go and for the rest mesh.
// Without a take: the rest mesh's lowest point. size 0 without a mesh.
Floor floorOf(const Document& document, const Eigen::Vector3d& up);

// A square grid of lines lying on the floor, under the subject. Not pickable.
class FloorGrid {
  public:
    FloorGrid();
    ~FloorGrid();
    vtkActor* actor() const;
    void set(const Floor& floor);
    // The height (along the floor's up) of the lines drawn, NaN when none are.
    double drawnHeight() const;

  private:
    Floor floor_;
    vtkNew<vtkPolyData> lines_;
    vtkNew<vtkPolyDataMapper> mapper_;
    vtkNew<vtkActor> actor_;
};

}  // namespace boneless::ui
