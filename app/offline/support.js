/* The support's figures in the offline page: a contact's data into the top view, Fig. 7,
 * the energy bars and the player's frames (the player's callbacks then redraw the frame on
 * show), and the rehearsal that readies them for the first key press.
 *
 *   var figures = MicropillarSupportFigures(CONFIG, models);   // models.js's
 *   figures.draw(r);                  // r: a contact (arrays.js, "contact"), not an error
 *   figures.rehearse(other, r, still, onStep);
 *
 * The rehearsal: a page's first key presses took about twice as long as the later ones
 * (V8 had not yet compiled BokehJS's paths for new data and their paint: a median of 51 ms
 * against 31 ms, docs/offline.md). Once the page is idle, ``rehearse`` draws another
 * contact (``other``: theta0 one degree on) and then ``r`` again in the same task, so each
 * animation frame paints ``r`` as it was (nothing changes on screen), ``REHEARSALS``
 * times, each after the last paint (6 left the first press at a median of 40 ms, 12 at
 * 28). It stops as soon as ``still()`` is false (a key press, a new state);
 * ``onStep(n)`` follows it (n rehearsals made).
 */
(function (root) {
  "use strict";
  var VIEWS = root.MicropillarViews;
  var REHEARSALS = 12;

  root.MicropillarSupportFigures = function (CONFIG, models) {
    function source(name) { return models.source(name); }
    function figure(name) { return models.figure(name); }

    function draw(r) {
      var s = r.series, p = r.params;
      models.setData(VIEWS.sceneData(s, p.theta0, CONFIG));
      var box = VIEWS.viewBox(s, CONFIG), scene = figure("scene");
      models.range(scene, "x_range", [box[0], box[1]]);
      models.range(scene, "y_range", [box[2], box[3]]);
      models.setData(VIEWS.forceData(s));
      var forcesX = VIEWS.forceXRange(s);
      models.range(figure("forces"), "x_range", forcesX);
      models.model("forces_mu0_label").setv({x: forcesX[1]});  // mu0's label at the end
      models.range(figure("forces"), "y_range", VIEWS.forceYRange(s, CONFIG.mu0));
      var energies = VIEWS.energyFrames(s, CONFIG);
      models.range(figure("energy_live"), "y_range", energies.range);
      var frames = VIEWS.supportFrames(s, p, CONFIG);
      source("support_player_times").data = {t: frames.support_frames.tau};
      // New data redraw the current frame (the player's callbacks follow these sources).
      source("energy_live_frames").data = energies.frames;
      source("support_frames").data = frames.support_frames;
      source("support_frame_params").data = frames.support_frame_params;
      return frames;
    }

    function rehearse(other, r, still, onStep) {
      var n = 0;
      function step() {
        if (n >= REHEARSALS || !still()) return;
        draw(other);
        draw(r);
        n += 1;
        if (onStep) onStep(n);
        // The next one after this frame's paint (a hidden page gets no frames: it stops).
        root.requestAnimationFrame(function () { root.setTimeout(step, 0); });
      }
      step();
    }

    return {draw: draw, rehearse: rehearse};
  };
  root.MicropillarSupportFigures.REHEARSALS = REHEARSALS;
}(this));
