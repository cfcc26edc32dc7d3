//! The eframe app: modes, keys, overlays, presenter view.
