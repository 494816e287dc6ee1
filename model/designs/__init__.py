"""Real designs: orientation distributions and their arrays, pillars in physical units, where a design sits on the map and the distribution that minimises friction."""
