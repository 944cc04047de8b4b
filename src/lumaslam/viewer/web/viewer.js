'use strict';
// The viewer page: server-sent events from /events carry /status.json's body; a new frame
// version reloads the two pictures, a new map version reloads /map.json into the 3D view.
const byId = (id) => document.getElementById(id);
const kHistory = 300;  // frames in the plots
const history = [];
let shownFrameVersion = -1;
let shownMapVersion = -1;
let mapRequest = null;

const kMapColours = [0x88c0d0, 0xa3be8c, 0xd08770, 0xb48ead, 0xebcb8b];
const kStageColours = { enhance: '#ebcb8b', features: '#88c0d0', tracking: '#a3be8c',
                        mapping: '#b48ead', detection_wait: '#d08770' };

function createMapView(canvas) {
  if (typeof THREE === 'undefined') {
    byId('map-note').textContent = 'three.js not served (Debian package libjs-three): no 3D view';
    return null;
  }
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setClearColor(0x111418);
  const scene = new THREE.Scene();
  const world = new THREE.Group();
  world.rotation.x = Math.PI;  // camera convention (y down, z forward) to y up
  scene.add(world);
  const camera = new THREE.PerspectiveCamera(60, canvas.width / canvas.height, 0.01, 5000);
  camera.position.set(0, 3, 3);
  const controls = THREE.OrbitControls ? new THREE.OrbitControls(camera, canvas) : null;
  let fitted = false;
  const layers = {};

  function replace(name, object) {
    if (layers[name]) {
      world.remove(layers[name]);
      layers[name].geometry.dispose();
    }
    layers[name] = object;
    world.add(object);
  }

  function colouredPoints(xyz, maps) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
    const colours = [];
    const colour = new THREE.Color();
    for (const map of maps) {
      colour.setHex(kMapColours[map % kMapColours.length]);
      colours.push(colour.r, colour.g, colour.b);
    }
    geometry.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
    return new THREE.Points(geometry, new THREE.PointsMaterial(
        { size: 2, sizeAttenuation: false, vertexColors: THREE.VertexColors }));
  }

  function segments(xyz, colour, opacity) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
    return new THREE.LineSegments(geometry, new THREE.LineBasicMaterial(
        { color: colour, transparent: opacity < 1, opacity }));
  }

  function keyframeCentre(poses, i) { return [poses[12 * i + 9], poses[12 * i + 10], poses[12 * i + 11]]; }

  function toWorld(poses, i, p) {
    const r = poses.slice(12 * i, 12 * i + 9);
    const t = keyframeCentre(poses, i);
    return [r[0] * p[0] + r[1] * p[1] + r[2] * p[2] + t[0],
            r[3] * p[0] + r[4] * p[1] + r[5] * p[2] + t[1],
            r[6] * p[0] + r[7] * p[1] + r[8] * p[2] + t[2]];
  }

  function frustums(poses, count, size) {
    const corners = [[-1, -0.75, 1.2], [1, -0.75, 1.2], [1, 0.75, 1.2], [-1, 0.75, 1.2]]
        .map((c) => c.map((v) => v * size));
    const xyz = [];
    for (let i = 0; i < count; ++i) {
      const o = keyframeCentre(poses, i);
      const w = corners.map((c) => toWorld(poses, i, c));
      for (let k = 0; k < 4; ++k) {
        xyz.push(...o, ...w[k], ...w[k], ...w[(k + 1) % 4]);
      }
    }
    return xyz;
  }

  function edges(poses, pairs) {
    const xyz = [];
    for (let k = 0; k + 1 < pairs.length; k += 2) {
      xyz.push(...keyframeCentre(poses, pairs[k]), ...keyframeCentre(poses, pairs[k + 1]));
    }
    return xyz;
  }

  function fit(xyz) {
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(xyz, 3));
    geometry.computeBoundingSphere();
    const sphere = geometry.boundingSphere;
    geometry.dispose();
    if (!sphere || !(sphere.radius > 0)) return 1;
    const centre = sphere.center.clone().applyMatrix4(world.matrixWorld);
    if (!fitted) {
      camera.position.copy(centre).add(new THREE.Vector3(0, sphere.radius, 2 * sphere.radius));
      if (controls) controls.target.copy(centre);
      camera.lookAt(centre);
      fitted = true;
    }
    return sphere.radius;
  }

  function update(snapshot) {
    const trajectory = snapshot.trajectory || [];
    const map = snapshot.map;
    if (map && map.points.length) {
      world.updateMatrixWorld();
      const radius = fit(map.points.concat(trajectory));
      replace('points', colouredPoints(map.points, map.point_maps));
      replace('keyframes', segments(frustums(map.poses, map.keyframes, radius * 0.02), 0x5e81ac, 1));
      replace('covisibility', segments(edges(map.poses, map.covisibility), 0xa3be8c, 0.35));
      replace('loops', segments(edges(map.poses, map.loops), 0xbf616a, 1));
    }
    if (trajectory.length >= 6) {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(trajectory, 3));
      replace('trajectory', new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: 0xd08770 })));
    }
  }

  function draw() {
    if (controls) controls.update();
    renderer.render(scene, camera);
  }

  (function render() {
    draw();
    requestAnimationFrame(render);
  })();
  // Drawn at once: a map given with the page is on the canvas when the page has loaded.
  return { update: (snapshot) => { update(snapshot); draw(); } };
}

function drawPlots(canvas) {
  const g = canvas.getContext('2d');
  const w = canvas.width;
  const h = canvas.height;
  g.fillStyle = '#111418';
  g.fillRect(0, 0, w, h);
  if (history.length < 1) return;
  const first = history[0].frame;
  const last = Math.max(history[history.length - 1].frame, first + 1);
  const x = (frame) => 40 + (w - 50) * (frame - first) / (last - first);
  const band = (top, bottom, values, max, colour) => {
    g.strokeStyle = colour;
    g.beginPath();
    history.forEach((s, k) => {
      const y = bottom - (bottom - top) * Math.min(values(s) / max, 1);
      if (k === 0) g.moveTo(x(s.frame), y); else g.lineTo(x(s.frame), y);
    });
    g.stroke();
  };
  const maxInliers = Math.max(50, ...history.map((s) => s.inliers || 0));
  g.fillStyle = '#d8dee9';
  g.fillText('inliers (max ' + maxInliers + ')', 44, 36);
  band(40, 170, (s) => s.inliers || 0, maxInliers, '#eceff4');
  const maxMs = Math.max(5, ...history.map((s) => (s.timing ? s.timing.total : 0)));
  g.fillText('ms per frame (max ' + maxMs.toFixed(1) + ')', 44, 196);
  band(200, 340, (s) => (s.timing ? s.timing.total : 0), maxMs, '#ffffff');
  for (const [stage, colour] of Object.entries(kStageColours)) {
    band(200, 340, (s) => (s.timing ? s.timing[stage] : 0), maxMs, colour);
  }
  history.forEach((s) => {  // tracking state strip
    g.fillStyle = s.state === 'ok' ? '#a3be8c' : '#bf616a';
    g.fillRect(x(s.frame), 360, Math.max(1, (w - 50) / history.length), 20);
  });
  g.fillStyle = '#d8dee9';
  g.fillText('tracked / lost', 44, 396);
}

function describe(status) {
  if (status.frame === undefined) return 'waiting for the first frame';
  const t = status.timing || {};
  return 'frame ' + status.frame + ' · ' + status.state + (status.step ? ' (' + status.step + ')' : '') +
      ' · ' + status.inliers + ' inliers · ' + status.kept + ' kept, ' + status.dropped +
      ' dropped · map ' + status.map + ': ' + status.keyframes + ' keyframes, ' +
      status.map_points + ' points · ' + (t.total || 0).toFixed(1) + ' ms';
}

function onStatus(status, mapView) {
  byId('status').textContent = describe(status);
  const runState = byId('run-state');
  runState.textContent = status.paused ? 'paused' : status.status;
  runState.className = status.paused ? 'paused' : '';
  if (status.frame !== undefined && status.frame_version !== shownFrameVersion) {
    shownFrameVersion = status.frame_version;
    byId('frame-raw').src = '/frame.jpg?view=raw&v=' + status.frame_version;
    byId('frame-enhanced').src = '/frame.jpg?view=enhanced&v=' + status.frame_version;
    byId('right-figure').hidden = !status.right;
    if (status.right) byId('frame-right').src = '/frame.jpg?view=right&v=' + status.frame_version;
    if (!history.length || history[history.length - 1].frame < status.frame) history.push(status);
    if (history.length > kHistory) history.shift();
    drawPlots(byId('plots'));
  }
  if (status.map_version !== shownMapVersion && mapView && !mapRequest) {
    shownMapVersion = status.map_version;
    mapRequest = fetch('/map.json').then((r) => r.json()).then((snapshot) => {
      mapView.update(snapshot);
    }).catch((error) => { byId('map-note').textContent = 'map: ' + error; })
      .finally(() => { mapRequest = null; });
  }
}

function control(action) {
  fetch('/control?action=' + action, { method: 'POST' });
}

(function start() {
  const mapView = createMapView(byId('map-view'));
  for (const action of ['pause', 'step', 'resume']) {
    byId(action).addEventListener('click', () => control(action));
  }
  drawPlots(byId('plots'));
  const initial = window.lumaslamInitialStatus;
  if (initial && window.lumaslamInitialMap && mapView) {
    shownMapVersion = initial.map_version;
    mapView.update(window.lumaslamInitialMap);
  }
  if (initial) onStatus(initial, mapView);
  // Every change as it happens, and the frames from before the page was opened.
  const events = new EventSource('/events');
  events.onmessage = (event) => onStatus(JSON.parse(event.data), mapView);
  events.onerror = () => {
    byId('run-state').textContent = 'disconnected (the run has ended?)';
  };
  fetch('/history.json').then((r) => r.json()).then((earlier) => {
    const known = new Set(history.map((s) => s.frame));
    history.push(...earlier.filter((s) => !known.has(s.frame)));
    history.sort((a, b) => a.frame - b.frame);
    while (history.length > kHistory) history.shift();
    drawPlots(byId('plots'));
  }).catch(() => {});
})();
