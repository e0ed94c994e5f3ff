#include "views/backdrop_cache.h"

#include <algorithm>
#include <vector>

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkDataObject.h>
#include <vtkImageData.h>
#include <vtkMapper.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkProp.h>
#include <vtkPropCollection.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkRendererCollection.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

namespace raystep::viz {

namespace {

// Everything the base layer's pixels depend on: the camera's values (not its modification time, which a
// clipping-range reset bumps), the window's size, the background, and each prop with its mapper and data.
struct Key {
  std::vector<double> camera;
  int size[2] = {0, 0};
  double background[3] = {0, 0, 0};
  std::vector<const void*> propList;  // which props (one removed or added back changes no time)
  vtkMTimeType props = 0;
  bool operator==(const Key& o) const {
    return camera == o.camera && size[0] == o.size[0] && size[1] == o.size[1] &&
           std::equal(background, background + 3, o.background) && props == o.props && propList == o.propList;
  }
};

Key keyOf(vtkRenderWindow* window, vtkRenderer* base) {
  Key k;
  vtkCamera* c = base->GetActiveCamera();
  double v[3];
  auto add = [&](const double* p, int n) { k.camera.insert(k.camera.end(), p, p + n); };
  c->GetPosition(v);
  add(v, 3);
  c->GetFocalPoint(v);
  add(v, 3);
  c->GetViewUp(v);
  add(v, 3);
  double range[2];
  c->GetClippingRange(range);
  add(range, 2);
  double scalars[3] = {c->GetViewAngle(), c->GetParallelScale(), double(c->GetParallelProjection())};
  add(scalars, 3);
  const int* size = window->GetSize();
  k.size[0] = size[0];
  k.size[1] = size[1];
  base->GetBackground(k.background);
  vtkPropCollection* props = base->GetViewProps();
  props->InitTraversal();
  while (vtkProp* p = props->GetNextProp()) {
    k.propList.push_back(p);
    k.props = std::max(k.props, p->GetMTime());
    if (auto* a = vtkActor::SafeDownCast(p); a && a->GetMapper()) {
      k.props = std::max(k.props, a->GetMapper()->GetMTime());
      if (vtkDataObject* in = a->GetMapper()->GetInputDataObject(0, 0)) k.props = std::max(k.props, in->GetMTime());
    }
  }
  return k;
}

}  // namespace

struct BackdropCache::Impl {
  vtkRenderWindow* window;
  vtkRenderer* base;
  std::vector<vtkRenderer*> above;
  vtkNew<vtkRenderer> backdrop;  // shows the image as its background, on the base's layer
  vtkNew<vtkTexture> texture;
  vtkNew<vtkImageData> image;
  vtkNew<vtkCallbackCommand> onStart, onEnd;
  int drawn = 0;  // renders that reached the end: a window not ready for rendering returns without drawing
  Key key;   // of the image
  Key seen;  // at the last prepare()
  bool cached = false;

  void live() {
    cached = false;
    backdrop->DrawOff();
    base->DrawOn();
  }
  static void ended(vtkObject*, unsigned long, void* self, void*) { ++static_cast<Impl*>(self)->drawn; }
  // Before any render: an interactive one (the camera turned) draws the base layer itself.
  static void started(vtkObject*, unsigned long, void* self, void*) {
    auto* d = static_cast<Impl*>(self);
    if (d->cached && !(keyOf(d->window, d->base) == d->key)) d->live();
  }
};

BackdropCache::BackdropCache(vtkRenderWindow* window, vtkRenderer* base, std::vector<vtkRenderer*> above)
    : d_(new Impl) {
  Impl& d = *d_;
  d.window = window;
  d.base = base;
  d.above = std::move(above);
  d.backdrop->SetLayer(base->GetLayer());
  d.backdrop->InteractiveOff();
  d.backdrop->DrawOff();
  d.texture->InterpolateOff();  // texel for pixel: the image comes back exactly
  d.texture->SetColorModeToDirectScalars();
  d.texture->SetInputData(d.image);
  d.backdrop->SetBackgroundTexture(d.texture);
  d.backdrop->TexturedBackgroundOn();
  window->AddRenderer(d.backdrop);
  d.onStart->SetCallback(&Impl::started);
  d.onStart->SetClientData(&d);
  window->AddObserver(vtkCommand::StartEvent, d.onStart);
  d.onEnd->SetCallback(&Impl::ended);
  d.onEnd->SetClientData(&d);
  window->AddObserver(vtkCommand::EndEvent, d.onEnd);
}

BackdropCache::~BackdropCache() {
  d_->window->RemoveObserver(d_->onStart);
  d_->window->RemoveObserver(d_->onEnd);
  d_->window->RemoveRenderer(d_->backdrop);
}

bool BackdropCache::cached() const { return d_->cached; }

void BackdropCache::drop() { d_->live(); }

void BackdropCache::prepare(bool ready) {
  Impl& d = *d_;
  const int* size = d.window->GetSize();
  if (!ready || size[0] < 2 || size[1] < 2) {
    d.live();
    return;
  }
  Key now = keyOf(d.window, d.base);
  if (d.cached && now == d.key) return;
  // A view that has just changed may go on changing (the camera following the walk): draw it directly, and
  // take the image only when a step finds it unchanged.
  if (!(now == d.seen)) {
    d.seen = now;
    d.live();
    return;
  }
  // Draw the base layer alone and keep its pixels.
  d.live();
  std::vector<int> draw;
  for (vtkRenderer* r : d.above) {
    draw.push_back(r->GetDraw());
    r->DrawOff();
  }
  int before = d.drawn;
  d.window->Render();
  if (d.drawn == before) {  // nothing was drawn: the pixels would be an older frame's
    for (size_t i = 0; i < d.above.size(); ++i) d.above[i]->SetDraw(draw[i]);
    return;
  }
  vtkNew<vtkUnsignedCharArray> pixels;
  int w = size[0], h = size[1];
  d.window->GetPixelData(0, 0, w - 1, h - 1, 0, pixels, 0);
  for (size_t i = 0; i < d.above.size(); ++i) d.above[i]->SetDraw(draw[i]);
  if (pixels->GetNumberOfTuples() != vtkIdType(w) * h || pixels->GetNumberOfComponents() != 3) return;  // live
  d.image->SetDimensions(w, h, 1);
  d.image->GetPointData()->SetScalars(pixels);
  d.image->Modified();
  d.key = keyOf(d.window, d.base);
  d.cached = true;
  d.base->DrawOff();
  d.backdrop->DrawOn();
}

}  // namespace raystep::viz
