"""The compiled engine: arrays (state), queue, grid, prediction, contact and the loop."""
