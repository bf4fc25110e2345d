"""What a run turns into: report formats, the SVG tree, the model summary, run reporting."""
