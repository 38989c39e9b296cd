//! family viscosity
