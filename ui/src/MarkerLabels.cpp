#include "MarkerLabels.h"

#include <vtkActor2D.h>
#include <vtkLabeledDataMapper.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkStringArray.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>

#include <algorithm>
#include <numeric>

namespace boneless::ui {

MarkerLabels::MarkerLabels() {
    mapper_->SetInputData(shown_);
    mapper_->SetLabelModeToLabelFieldData();
    mapper_->SetFieldDataName("label");
    vtkTextProperty* text = mapper_->GetLabelTextProperty();
    text->SetFontSize(13);
    text->SetBold(false);
    text->SetItalic(false);
    text->SetColor(1.0, 1.0, 0.85);
    text->ShadowOn();
    // Measured boxes and drawn text share this anchoring: left and bottom at the marker.
    text->SetJustificationToLeft();
    text->SetVerticalJustificationToBottom();
    actor_->SetMapper(mapper_);
    actor_->VisibilityOff();
}

MarkerLabels::~MarkerLabels() = default;

vtkActor2D* MarkerLabels::actor() const {
    return actor_.Get();
}

void MarkerLabels::set(const Positions& points, const std::vector<std::string>& texts,
                       const std::vector<int>& priorities) {
    points_ = points;
    texts_ = texts;
    priorities_ = priorities;
    texts_.resize(points.rows());
    priorities_.resize(points.rows(), 0);
    actor_->SetVisibility(visible_ && points_.rows() > 0);
}

void MarkerLabels::setVisible(bool visible) {
    visible_ = visible;
    actor_->SetVisibility(visible_ && points_.rows() > 0);
}

void MarkerLabels::layout(vtkRenderer* renderer) {
    drawn_.clear();
    hidden_ = 0;
    if (!actor_->GetVisibility()) return;
    vtkTextRenderer* measure = vtkTextRenderer::GetInstance();
    vtkRenderWindow* window = renderer->GetRenderWindow();
    const int dpi = window ? window->GetDPI() : 72;
    const int* size = window ? window->GetSize() : nullptr;
    std::vector<int> order(points_.rows());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return priorities_[a] < priorities_[b]; });
    vtkNew<vtkPoints> points;
    vtkNew<vtkStringArray> labels;
    labels->SetName("label");
    for (int k : order) {
        renderer->SetWorldPoint(points_(k, 0), points_(k, 1), points_(k, 2), 1.0);
        renderer->WorldToDisplay();
        double d[3];
        renderer->GetDisplayPoint(d);
        int bbox[4];
        // Behind the camera, off screen or not measurable: not drawn, and not counted as hidden.
        if (d[2] < 0 || d[2] > 1 ||
            (size && (d[0] < 0 || d[1] < 0 || d[0] >= size[0] || d[1] >= size[1])))
            continue;
        if (!measure ||
            !measure->GetBoundingBox(mapper_->GetLabelTextProperty(), texts_[k], bbox, dpi))
            continue;
        const int x = int(d[0]), y = int(d[1]);
        const LabelBox box{x + bbox[0], y + bbox[2], x + bbox[1] + 1, y + bbox[3] + 1};
        if (std::any_of(drawn_.begin(), drawn_.end(),
                        [&](const LabelBox& b) { return b.overlaps(box); })) {
            ++hidden_;
            continue;
        }
        drawn_.push_back(box);
        points->InsertNextPoint(points_(k, 0), points_(k, 1), points_(k, 2));
        labels->InsertNextValue(texts_[k]);
    }
    shown_->Initialize();
    shown_->SetPoints(points);
    shown_->GetPointData()->AddArray(labels);
    shown_->Modified();
}

}  // namespace boneless::ui
