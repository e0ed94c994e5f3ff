// The 3D view's backdrop: the scene and the structure's outline change only when the camera, the window's size
// or the scene does, while a step changes only the walk drawn over them. Under software OpenGL (llvmpipe)
// drawing a 70k-triangle mesh is most of a step's redraw, so the base layer is drawn once into an image, and
// while nothing of it changes, a second renderer on the same layer shows that image as its background in its
// place. After any change (the camera, the size, an actor of the base layer or its data) a step draws the base
// layer directly, and the next step that finds it unchanged takes a new image (so a camera that follows the
// walk costs no more than drawing everything); an interactive render in between (the user turning the camera)
// draws it directly. The image is the base layer's own pixels, so the picture is the same either way.
#pragma once

#include <array>
#include <memory>
#include <vector>

class vtkRenderWindow;
class vtkRenderer;

namespace raystep::viz {

class BackdropCache {
 public:
  // `base` is drawn into the image; the renderers `above` it (higher layers) are left out of it. All stay the
  // caller's.
  BackdropCache(vtkRenderWindow* window, vtkRenderer* base, std::vector<vtkRenderer*> above);
  ~BackdropCache();
  BackdropCache(const BackdropCache&) = delete;
  BackdropCache& operator=(const BackdropCache&) = delete;

  // Call before the window's Render() for a step: keeps the image, or draws the base layer and takes a new one.
  // `ready`: the window has a current, sized OpenGL context (false: everything is drawn directly).
  void prepare(bool ready);
  // Draw everything directly from now on, until the next prepare().
  void drop();
  bool cached() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

}  // namespace raystep::viz
