arch	im	records	censored	median	beta	median_lo	median_hi
oppenheim	pga_g	1	0	nan	nan	nan	nan
oppenheim	pgv_m_s	1	0	nan	nan	nan	nan
oppenheim	pgd_m	1	0	nan	nan	nan	nan
oppenheim	arias_m_s	1	0	nan	nan	nan	nan
oppenheim	cav_m_s	1	0	nan	nan	nan	nan
oppenheim	pga_lambda0	1	0	nan	nan	nan	nan
