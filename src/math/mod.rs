//! Typeset maths for slides, in-process and offline.
