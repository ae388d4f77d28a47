#pragma once

#include <string>
#include <vector>

#include <vtkNew.h>

#include "boneless/TriMesh.h"

class vtkActor2D;
class vtkLabeledDataMapper;
class vtkPolyData;
class vtkRenderer;

namespace boneless::ui {

// A label's place on screen: VTK display pixels (origin bottom-left), inclusive-exclusive.
struct LabelBox {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool overlaps(const LabelBox& o) const {
        return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
    }
};

// Marker labels that do not pile up: before each render, layout() measures every label where
// its marker projects and draws only those that overlap no label of higher priority, so the
// selected marker's name always shows and crowded ones give way.
class MarkerLabels {
  public:
    MarkerLabels();
    ~MarkerLabels();
    vtkActor2D* actor() const;

    // One entry per point; a lower priority number is drawn first.
    void set(const Positions& points, const std::vector<std::string>& texts,
             const std::vector<int>& priorities);
    void setVisible(bool visible);
    bool visible() const { return visible_; }
    // Chooses the labels for the renderer's current camera and size.
    void layout(vtkRenderer* renderer);
    // The boxes of the labels drawn by the last layout(), and how many were left out.
    const std::vector<LabelBox>& drawnBoxes() const { return drawn_; }
    int hiddenCount() const { return hidden_; }

  private:
    Positions points_;
    std::vector<std::string> texts_;
    std::vector<int> priorities_;
    bool visible_ = false;
    std::vector<LabelBox> drawn_;
    int hidden_ = 0;
    vtkNew<vtkPolyData> shown_;
    vtkNew<vtkLabeledDataMapper> mapper_;
    vtkNew<vtkActor2D> actor_;
};

}  // namespace boneless::ui
