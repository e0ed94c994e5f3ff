// The browser player's 3D view (bundled with three.js by esbuild into the page as the global raystepView3d):
// the scene's triangles and spheres, seen through, the ray with its current [t_min, t_max] thick, and the
// walk's boxes at the step: the current cell or node filled yellow, the nodes on the stack pink, the leaves
// and cells visited before in pale blue, as the debugger's 3D view colours them. Drag to orbit, wheel to zoom.
// It shows what the page's data says at the step; it traverses nothing.
import * as THREE from 'three';

const colours = { current: 0xf2c200, stack: 0xe0609a, visited: 0x6f9fe0, ray: 0xd01818, mesh: 0xb8b8c0 };

export function createView(container, scene3d) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xffffff);
  scene.add(new THREE.AmbientLight(0xffffff, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  scene.add(sun);

  const b = scene3d ? scene3d.bounds : [-1, -1, -1, 1, 1, 1];
  const lo = new THREE.Vector3(b[0], b[1], b[2]), hi = new THREE.Vector3(b[3], b[4], b[5]);
  const centre = lo.clone().add(hi).multiplyScalar(0.5);
  const size = Math.max(hi.clone().sub(lo).length(), 1e-6);

  if (scene3d) {  // the scene, seen through so that the boxes inside show
    const material = new THREE.MeshLambertMaterial({ color: colours.mesh, transparent: true, opacity: 0.35,
                                                     depthWrite: false, side: THREE.DoubleSide });
    if (scene3d.triangles.length) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(scene3d.triangles, 3));
      g.computeVertexNormals();
      scene.add(new THREE.Mesh(g, material));
    }
    for (const [x, y, z, r] of scene3d.spheres) {
      const m = new THREE.Mesh(new THREE.SphereGeometry(r, 32, 16), material);
      m.position.set(x, y, z);
      scene.add(m);
    }
  }

  const camera = new THREE.PerspectiveCamera(40, 1, size * 1e-3, size * 100);
  const orbit = { target: centre.clone(), distance: 1.6 * size, theta: 0.6, phi: 1.1 };
  function place() {
    const s = Math.sin(orbit.phi);
    camera.position.set(orbit.target.x + orbit.distance * s * Math.sin(orbit.theta),
                        orbit.target.y + orbit.distance * Math.cos(orbit.phi),
                        orbit.target.z + orbit.distance * s * Math.cos(orbit.theta));
    camera.lookAt(orbit.target);
    sun.position.copy(camera.position);
  }

  const walkGroup = new THREE.Group();
  scene.add(walkGroup);
  let walk = null;
  const shown = { current: -1, stack: 0, visited: 0 };

  function boxMesh(box, colour, filled) {
    const [x0, y0, z0, x1, y1, z1] = box;
    const g = new THREE.BoxGeometry(Math.max(x1 - x0, 1e-9), Math.max(y1 - y0, 1e-9), Math.max(z1 - z0, 1e-9));
    const group = new THREE.Group();
    group.add(new THREE.LineSegments(new THREE.EdgesGeometry(g), new THREE.LineBasicMaterial({ color: colour })));
    if (filled)
      group.add(new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: colour, transparent: true, opacity: filled,
                                                                 depthWrite: false })));
    group.position.set((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2);
    return group;
  }
  function segment(a, b, radius, colour) {
    const d = b.clone().sub(a);
    const m = new THREE.Mesh(new THREE.CylinderGeometry(radius, radius, Math.max(d.length(), 1e-9), 10),
                             new THREE.MeshBasicMaterial({ color: colour }));
    m.position.copy(a.clone().add(b).multiplyScalar(0.5));
    m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), d.normalize());
    return m;
  }

  function setRay(w) {
    walk = w;
    // A primary ray starts at the camera: look from near its origin, turned a little aside so that the ray
    // shows as a line rather than a point.
    if (w) {
      const o = new THREE.Vector3(...w.origin);
      const v = o.clone().sub(orbit.target);
      if (v.length() > 1e-6) {
        orbit.distance = Math.max(v.length() * 1.1, 0.5 * size);
        orbit.phi = Math.max(0.05, Math.acos(Math.max(-1, Math.min(1, v.y / v.length()))) - 0.25);
        orbit.theta = Math.atan2(v.x, v.z) + 0.5;
      }
    }
  }

  function setStep(k) {
    walkGroup.clear();
    if (!walk) return render();
    const o = new THREE.Vector3(...walk.origin), d = new THREE.Vector3(...walk.direction);
    const far = walk.hit_t !== null ? walk.hit_t : (o.distanceTo(centre) + size) / Math.max(d.length(), 1e-30);
    walkGroup.add(segment(o, o.clone().addScaledVector(d, far), size * 0.0015, colours.ray));
    const iv = walk.interval[k];
    if (iv) walkGroup.add(segment(o.clone().addScaledVector(d, Math.max(0, iv[0])),
                                  o.clone().addScaledVector(d, Math.min(iv[1], far)), size * 0.005, colours.ray));
    if (walk.hit_t !== null && k === walk.current.length - 1) {
      const dot = new THREE.Mesh(new THREE.SphereGeometry(size * 0.008, 16, 8), new THREE.MeshBasicMaterial({ color: colours.ray }));
      dot.position.copy(o.clone().addScaledVector(d, walk.hit_t));
      walkGroup.add(dot);
    }
    // Visited: the leaves and cells that were current before this step.
    const visited = new Set();
    for (let j = 0; j < k; ++j) {
      const c = walk.current[j];
      if (c >= 0 && walk.boxes[c][6] && c !== walk.current[k]) visited.add(c);
    }
    for (const c of visited) walkGroup.add(boxMesh(walk.boxes[c], colours.visited, 0.12));
    for (const s of walk.stack[k]) walkGroup.add(boxMesh(walk.boxes[s], colours.stack, 0.1));
    const cur = walk.current[k];
    if (cur >= 0) walkGroup.add(boxMesh(walk.boxes[cur], colours.current, 0.3));
    shown.current = cur;
    shown.stack = walk.stack[k].length;
    shown.visited = visited.size;
    render();
  }

  function resize() {
    const w = Math.max(200, container.clientWidth), h = Math.round(w * 0.75);
    renderer.setSize(w, h);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
    render();
  }
  function render() {
    place();
    renderer.render(scene, camera);
  }

  // Drag to orbit, wheel to zoom.
  let drag = null;
  renderer.domElement.addEventListener('pointerdown', (e) => {
    drag = { x: e.clientX, y: e.clientY };
    renderer.domElement.setPointerCapture(e.pointerId);
  });
  renderer.domElement.addEventListener('pointermove', (e) => {
    if (!drag) return;
    orbit.theta -= (e.clientX - drag.x) * 0.008;
    orbit.phi = Math.max(0.05, Math.min(Math.PI - 0.05, orbit.phi - (e.clientY - drag.y) * 0.008));
    drag = { x: e.clientX, y: e.clientY };
    render();
  });
  renderer.domElement.addEventListener('pointerup', () => { drag = null; });
  renderer.domElement.addEventListener('wheel', (e) => {
    e.preventDefault();
    orbit.distance *= Math.exp(e.deltaY * 0.001);
    render();
  }, { passive: false });
  window.addEventListener('resize', resize);
  resize();
  return { setRay, setStep, shown, canvas: renderer.domElement };
}
