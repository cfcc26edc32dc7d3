//! Rigid bodies: the 13-number state (x, q, P, L), body-space inertia from a closed triangle
//! mesh (Mirtich 1996) or a point lattice, and the forces the water scene needs.
