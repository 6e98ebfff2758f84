//! Backend-agnostic debug drawing for Rebound: what to draw for colliders, bounding boxes, contacts and joints.
