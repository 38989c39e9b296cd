//! family turbulence
