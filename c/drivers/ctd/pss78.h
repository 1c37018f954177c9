/* Practical salinity (PSS-78) and depth from pressure (UNESCO 1983: Fofonoff
 * and Millard, "Algorithms for computation of fundamental properties of
 * seawater", UNESCO technical papers in marine science 44), for a CTD whose
 * scans carry no salinity (the SBE 49's hex format): the vehicle has no
 * TEOS-10 library in C, and PSS-78 is what the instrument's own software
 * computes. The simulator's CTD derives its salinity with gsw.SP_from_C, the
 * same standard: the tests hold the two together. */
#ifndef DRV_PSS78_H
#define DRV_PSS78_H

/* Conductivity [S/m], in-situ temperature [degC, ITS-90], sea pressure [dbar]
 * -> practical salinity [PSU]; NaN outside PSS-78's range of validity (2 to 42)
 * or for a conductivity under 0. */
double pss78_salinity(double conductivity_s_per_m, double temperature_c, double pressure_dbar);
/* Depth [m] of a sea pressure [dbar] at a latitude [deg] (UNESCO 1983). */
double pss78_depth(double pressure_dbar, double latitude_deg);

#endif
