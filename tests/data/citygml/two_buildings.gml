<?xml version="1.0" encoding="UTF-8"?>
<!-- A hand-made CityGML 2.0 district for the CityGML reader's tests (tests/geometry/CityGmlTest.cpp):
     DEBY_B1, a gabled LoD2 house (10 x 8 m, ground 100 m, eaves 106 m, ridge 109 m) whose
     lod2Solid refers to its boundedBy polygons by xlink, with a balcony (an installation, not
     part of its volume); DEBY_B2, a LoD1 block (6 x 6 m, 12 m tall) with a LoD1 building part
     (4 x 4 m, 20 m tall). The reference system is compound, as German LoD2 data gives it;
     DEBY_B1 carries a generic attribute "tile" (what the payload option reads). -->
<core:CityModel xmlns:core="http://www.opengis.net/citygml/2.0" xmlns:bldg="http://www.opengis.net/citygml/building/2.0" xmlns:gml="http://www.opengis.net/gml" xmlns:gen="http://www.opengis.net/citygml/generics/2.0" xmlns:xlink="http://www.w3.org/1999/xlink">
  <gml:boundedBy>
    <gml:Envelope srsName="urn:ogc:def:crs,crs:EPSG::25832,crs:EPSG::7837" srsDimension="3">
      <gml:lowerCorner>0 0 100</gml:lowerCorner>
      <gml:upperCorner>30 8 120</gml:upperCorner>
    </gml:Envelope>
  </gml:boundedBy>
  <core:cityObjectMember>
    <bldg:Building gml:id="DEBY_B1">
      <gen:stringAttribute name="tile"><gen:value>tile-17</gen:value></gen:stringAttribute>
      <bldg:measuredHeight uom="urn:adv:uom:m">9</bldg:measuredHeight>
      <bldg:lod2Solid>
        <gml:Solid>
          <gml:exterior>
            <gml:CompositeSurface>
              <gml:surfaceMember xlink:href="#B1_ground"/>
              <gml:surfaceMember xlink:href="#B1_south"/>
              <gml:surfaceMember xlink:href="#B1_north"/>
              <gml:surfaceMember xlink:href="#B1_east"/>
              <gml:surfaceMember xlink:href="#B1_west"/>
              <gml:surfaceMember xlink:href="#B1_roof_s"/>
              <gml:surfaceMember xlink:href="#B1_roof_n"/>
            </gml:CompositeSurface>
          </gml:exterior>
        </gml:Solid>
      </bldg:lod2Solid>
      <bldg:outerBuildingInstallation>
        <bldg:BuildingInstallation gml:id="DEBY_B1_balcony">
          <bldg:lod2Geometry><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_balcony"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">2 -2 103 6 -2 103 6 0 103 2 0 103 2 -2 103</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2Geometry>
        </bldg:BuildingInstallation>
      </bldg:outerBuildingInstallation>
      <bldg:boundedBy>
        <bldg:GroundSurface gml:id="B1_ground_s">
          <bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_ground"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">0 0 100 0 8 100 10 8 100 10 0 100 0 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:GroundSurface>
      </bldg:boundedBy>
      <bldg:boundedBy>
        <bldg:WallSurface gml:id="B1_south_s">
          <bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_south"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">0 0 100 10 0 100 10 0 106 0 0 106 0 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:WallSurface>
      </bldg:boundedBy>
      <bldg:boundedBy>
        <bldg:WallSurface gml:id="B1_north_s">
          <bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_north"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">10 8 100 0 8 100 0 8 106 10 8 106 10 8 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:WallSurface>
      </bldg:boundedBy>
      <bldg:boundedBy>
        <bldg:WallSurface gml:id="B1_east_s">
          <bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_east"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">10 0 100 10 8 100 10 8 106 10 4 109 10 0 106 10 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:WallSurface>
      </bldg:boundedBy>
      <bldg:boundedBy>
        <bldg:WallSurface gml:id="B1_west_s">
          <bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_west"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">0 8 100 0 0 100 0 0 106 0 4 109 0 8 106 0 8 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:WallSurface>
      </bldg:boundedBy>
      <bldg:boundedBy>
        <bldg:RoofSurface gml:id="B1_roof_s_s">
          <bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_roof_s"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">0 0 106 10 0 106 10 4 109 0 4 109 0 0 106</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:RoofSurface>
      </bldg:boundedBy>
      <bldg:boundedBy>
        <bldg:RoofSurface gml:id="B1_roof_n_s">
          <bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon gml:id="B1_roof_n"><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">10 8 106 0 8 106 0 4 109 10 4 109 10 8 106</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface>
        </bldg:RoofSurface>
      </bldg:boundedBy>
    </bldg:Building>
  </core:cityObjectMember>
  <core:cityObjectMember>
    <bldg:Building gml:id="DEBY_B2">
      <bldg:lod1Solid>
        <gml:Solid>
          <gml:exterior>
            <gml:CompositeSurface>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">20 0 100 20 6 100 26 6 100 26 0 100 20 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:pos>20 0 112</gml:pos><gml:pos>26 0 112</gml:pos><gml:pos>26 6 112</gml:pos><gml:pos>20 6 112</gml:pos><gml:pos>20 0 112</gml:pos></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">20 0 100 26 0 100 26 0 112 20 0 112 20 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">26 0 100 26 6 100 26 6 112 26 0 112 26 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">26 6 100 20 6 100 20 6 112 26 6 112 26 6 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">20 6 100 20 0 100 20 0 112 20 6 112 20 6 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
            </gml:CompositeSurface>
          </gml:exterior>
        </gml:Solid>
      </bldg:lod1Solid>
      <bldg:consistsOfBuildingPart>
        <bldg:BuildingPart gml:id="DEBY_B2_p1">
          <bldg:lod1Solid>
            <gml:Solid>
              <gml:exterior>
                <gml:CompositeSurface>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">26 0 100 26 4 100 30 4 100 30 0 100 26 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">26 0 120 30 0 120 30 4 120 26 4 120 26 0 120</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">26 0 100 30 0 100 30 0 120 26 0 120 26 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">30 0 100 30 4 100 30 4 120 30 0 120 30 0 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">30 4 100 26 4 100 26 4 120 30 4 120 30 4 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
              <gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing><gml:posList srsDimension="3">26 4 100 26 0 100 26 0 120 26 4 120 26 4 100</gml:posList></gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>
                </gml:CompositeSurface>
              </gml:exterior>
            </gml:Solid>
          </bldg:lod1Solid>
        </bldg:BuildingPart>
      </bldg:consistsOfBuildingPart>
    </bldg:Building>
  </core:cityObjectMember>
</core:CityModel>
