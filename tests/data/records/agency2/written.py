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


def nsmn():
    """Turkey's NSMN/AFAD ASCII as gmprocess's reader describes it (18 header
    lines, "KEY : value", RECORD TIME day/month/year, SAMPLING INTERVAL (sec),
    three columns N-S E-W U-D), with a place name in ISO-8859-9 bytes.  The
    values are written in gal, as the RAW PGA line says."""
    n, dt = 300, 0.01
    cols = [wave(n, dt, 187.654, 2.7, 0.2, 0.6), wave(n, dt, -143.21, 3.9, 0.9, 0.65),
            wave(n, dt, 61.5, 6.1, 0.4, 0.55)]
    rows = [[round(c[k], 6) for c in cols] for k in range(n)]
    pk = [max(abs(r[j]) for r in rows) for j in range(3)]
    head = [
        "STRONG GROUND MOTION RECORDS OF TURKIYE",
        "PLACE                          : Deneme \u0130stasyonu, G\u00fcne\u015fli (archquake test file, no agency data)",
        "EARTHQUAKE DATE                : 05/03/2011",
        "EARTHQUAKE TIME (GMT)          : 12:34:50",
        "EARTHQUAKE MAGNITUDE           : (none: test record)",
        "EPICENTER COORDINATES          : 40.0000N-30.0000E",
        "STATION ID                     : 9999",
        "STATION COORDINATES            : 40.1000N-30.1000E",
        "STATION ALTITUDE (m)           : 100",
        "RECORDER TYPE                  : (none)",
        "RECORDER SERIAL NO             : 0",
        "RECORD TIME                    : 05/03/2011 12:34:56.500000 (GMT)",
        "NUMBER OF DATA                 : %d" % n,
        "SAMPLING INTERVAL (sec)        : %g" % dt,
        "RAW PGA VALUES (gal)           : N-S: %.6f  E-W: %.6f  U-D: %.6f" % tuple(pk),
        "",
        "",
        "         N-S         E-W         U-D",
    ]
    body = ["".join("%12.6f" % x for x in r) for r in rows]
    with open("TK9999-20110305.txt", "wb") as fh:
        fh.write(("\r\n".join(head + body) + "\r\n").encode("iso8859_9"))
    for j, name in enumerate(("N-S", "E-W", "U-D")):
        print("TK9999-20110305.txt#%s npts %d dt %g peak %.6f gal = %.7g g" % (name, n, dt, pk[j], pk[j] / 100 / G0))


def npts_dt():
    """The two-number first line "NPTS DT" that OpenSees examples use, then
    the values (several to a line, the last line short), or one (time,
    value) pair to a line.  No units are stated (the values are in g)."""
    n, dt = 403, 0.02
    a = [round(x, 6) for x in wave(n, dt, 0.31234, 1.7, 0.5, 1.0)]
    lines = ["%d %g" % (n, dt)] + [" ".join("%.6f" % x for x in a[i:i + 5]) for i in range(0, n, 5)]
    with open("npts-dt-values.txt", "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("npts-dt-values.txt npts %d dt %g peak %.6f g" % (n, dt, max(abs(x) for x in a)))
    n, dt, t0 = 350, 0.005, 0.0
    a = [round(x, 7) for x in wave(n, dt, -0.0876, 4.2, 0.1, 0.4)]
    lines = ["%d  %g" % (n, dt)] + ["%.3f\t%.7f" % (t0 + k * dt, a[k]) for k in range(n)]
    with open("npts-dt-pairs.txt", "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("npts-dt-pairs.txt npts %d dt %g peak %.7f g" % (n, dt, max(abs(x) for x in a)))


if __name__ == "__main__":
    asa_cicese()
    nsmn()
    npts_dt()
