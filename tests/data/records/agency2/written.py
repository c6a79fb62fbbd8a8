#!/usr/bin/env python3
"""Write the small records of tests/data/records/agency2 that no public file
could stand for (PROVENANCE.md, "written"), and print the reference numbers
the provenance gives for them: npts, dt and max|a| in g, from the values as
written (rounded to the printed digits), independently of archquake.
Run from this directory: python3 written.py (it rewrites the files)."""
import math

G0 = 9.80665


def wave(n, dt, amp, f, phase, t0):
    """A decaying sine that starts at t0: deterministic test motion."""
    out = []
    for k in range(n):
        t = k * dt
        a = 0.0 if t < t0 else amp * math.sin(2 * math.pi * f * (t - t0) + phase) * math.exp(-(t - t0) / 0.6)
        out.append(a)
    return out


def asa_cicese():
    """ASA 2.0 in the CICESE layout as this project understands it: no
    institution banner, keys not padded to a fixed column, per-channel lists
    without the leading '/', the horizontal first and the vertical second,
    3F10.4 data.  Gal."""
    n, dt = 240, 0.01
    ch = [("N00W", wave(n, dt, 123.4567, 3.1, 0.3, 0.5)),
          ("V", wave(n, dt, 45.6789, 5.3, 1.1, 0.42)),
          ("N90W", wave(n, dt, -98.7654, 2.2, 0.7, 0.55))]
    rows = [[round(c[1][k], 4) for c in ch] for k in range(n)]
    head = [
        "ARCHIVO ESTANDAR DE ACELERACION",
        "VERSION DEL FORMATO: 2.0",
        "NOMBRE DEL ARCHIVO: PRUE1004.041",
        "INSTITUCION RESPONSABLE: archquake (written from the ASA 2.0 field list; no agency data)",
        "",
        "DATOS DE LA ESTACION",
        "NOMBRE DE LA ESTACION: ESTACION DE PRUEBA",
        "CLAVE DE LA ESTACION: PRUE",
        "COORDENADAS DE LA ESTACION: 32.0000 LAT. N",
        "                          : 115.0000 LONG. W",
        "",
        "DATOS DEL ACELEROGRAFO",
        "MODELO DEL ACELEROGRAFO: (ninguno)",
        "NUMERO DE CANALES: 3",
        "ORIENTACION C1-C6 (rumbo;orientacion): N00W/V/N90W",
        "VEL. DE MUESTREO, C1-C6 (muestras/s): 100/100/100",
        "INTERVALO DE MUESTREO, C1-C6 (s): 0.01/0.01/0.01",
        "",
        "DATOS DEL SISMO",
        "FECHA DEL SISMO (GMT): 2010/04/04",
        "HORA EPICENTRO (GMT): 23:59:50.0",
        "MAGNITUD(ES): (ninguna: registro de prueba)",
        "",
        "DATOS DE ESTE REGISTRO",
        "HORA DE LA PRIMERA MUESTRA (GMT): 00:00:07.25",
        "DURACION DEL REGISTRO (s), C1-C6: 2.40/2.40/2.40",
        "NUM. TOTAL DE MUESTRAS, C1-C6: 240/240/240",
        "UNIDADES DE LOS DATOS: cm/s/s",
        "FORMATO DATOS (FORTRAN,10 campos/dato): 3F10.4",
        "",
        "DATOS DE ACELERACION:",
        "      N00W         V      N90W",
    ]
    body = ["".join("%10.4f" % x for x in r) for r in rows]
    with open("PRUE1004.041", "w", newline="\r\n") as fh:
        fh.write("\n".join(head + body) + "\n")
    for j, (name, _) in enumerate(ch):
        pk = max(abs(r[j]) for r in rows)
        print("PRUE1004.041#%s npts %d dt %g peak %.4f gal = %.6g g" % (name, n, dt, pk, pk / 100 / G0))


if __name__ == "__main__":
    asa_cicese()
