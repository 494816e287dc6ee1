"""One function per figure, each drawing a Bokeh figure from plain data (model results).

The same functions draw the paper's figures outside the dashboard:

* ``scene_figure`` -- one support during a contact (Eqs. 1-6, 9);
* ``forces_figure`` -- friction time histories (Fig. 7);
* ``friction_law_figure`` -- mu(v) (Fig. 3);
* ``energy_figure`` -- the split of the slab work (Eq. 12, Fig. 8b style);
* ``polar_figure`` -- fixed arrays against theta0 as polar diagrams (Fig. 11a-c);
* ``regime_map_figure`` -- uniform arrays over (k_r, k_theta) (Fig. 5a/5b);
* ``load_figure`` -- uniform arrays against F_N (Fig. 6);
* ``contact_count_figure``, ``work_split_figure`` -- uniform arrays against k_r (Fig. 8a/b);
* ``components_figure``, ``radius_figure``, ``rms_figure`` -- supports of fixed arrays
  (Fig. 10a-d, 10e, 10f).

The module imports Bokeh only (no Panel): ``python -m model reproduce`` draws with it too.
"""
from .arrays import (load_curve_data, load_figure, load_now, load_regimes_data, map_data,
                     map_now, regime_map_figure, value_range)
from .common import annotation, sources, style, update
from .histories import (energy_data, energy_figure, force_data, force_now, force_x_range,
                        force_y_range, forces_figure, friction_law_figure, friction_now)
from .orientation import (components_data, components_figure, radius_figure, rms_data,
                          rms_figure)
from .polar import QUANTITIES as POLAR_QUANTITIES
from .polar import polar_data, polar_figure, polar_now, set_extent
from .scene import scene_data, scene_figure, scene_frame, time_text
from .stiffness import (contact_count_data, contact_count_figure, work_split_data,
                        work_split_figure)

__all__ = ["scene_figure", "scene_data", "scene_frame", "time_text", "forces_figure",
           "force_data", "force_now", "force_x_range", "force_y_range", "friction_law_figure", "friction_now", "energy_figure",
           "energy_data", "polar_figure", "polar_data", "polar_now", "set_extent",
           "POLAR_QUANTITIES", "regime_map_figure", "map_data", "map_now", "value_range",
           "load_figure", "load_curve_data", "load_regimes_data", "load_now", "annotation",
           "sources", "style", "update", "contact_count_figure", "contact_count_data",
           "work_split_figure", "work_split_data", "components_figure", "components_data",
           "radius_figure", "rms_figure", "rms_data"]
